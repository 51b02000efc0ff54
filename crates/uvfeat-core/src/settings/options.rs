//! The public names of a computation's options: each option's name, its value as the user writes
//! it, its choices and its default, in one place. The Python binding and the command line read
//! them from here (DESIGN.md §1.10), so a name or a default exists once.

use super::{ComputeSettings, VertexQuery};
use crate::error::{Result, UvfeatError};
use crate::features::{CurvatureMethod, GaussianMethod, VolumeWeighting};
use crate::lookup::Lookup;
use crate::raster::{Precision, Surface};
use crate::relocation::Relocation;
use crate::sampling::{Criterion, Geodesic, Overlaps, Quadrature, SamplingPath};

/// An option whose value is one of a few names.
pub trait Choice: Copy + PartialEq + Sized + 'static {
    /// The option's name.
    const OPTION: &'static str;
    /// Every value with its public name, the default first.
    const CHOICES: &'static [(&'static str, Self)];

    /// The public name of this value.
    fn name(self) -> &'static str {
        Self::CHOICES.iter().find(|(_, value)| *value == self).map_or("", |(name, _)| name)
    }

    /// The value of a public name.
    ///
    /// # Errors
    /// [`UvfeatError::InvalidParameter`] naming the option and its valid values.
    fn named(name: &str) -> Result<Self> {
        Self::CHOICES.iter().find(|(n, _)| *n == name).map(|(_, value)| *value).ok_or_else(|| {
            let valid: Vec<&str> = Self::CHOICES.iter().map(|(n, _)| *n).collect();
            UvfeatError::InvalidParameter { name: Self::OPTION, reason: format!("{name:?} is not one of {valid:?}") }
        })
    }

    /// The public names, the default first.
    fn names() -> Vec<&'static str> {
        Self::CHOICES.iter().map(|(name, _)| *name).collect()
    }
}

/// Implements [`Choice`] for an enum: `choice!(Type, "option", [("name", Type::Value), ...])`.
#[macro_export]
macro_rules! choice {
    ($kind:ty, $option:literal, [$(($name:literal, $value:expr)),+ $(,)?]) => {
        impl $crate::settings::Choice for $kind {
            const OPTION: &'static str = $option;
            const CHOICES: &'static [(&'static str, Self)] = &[$(($name, $value)),+];
        }
    };
}

crate::choice!(
    Relocation,
    "relocation",
    [("walk", Relocation::Walk), ("march", Relocation::March), ("per_chart", Relocation::PerChart)]
);
crate::choice!(Criterion, "criterion", [("euclidean", Criterion::Euclidean), ("geodesic", Criterion::Geodesic)]);
crate::choice!(Lookup, "lookup", [("triangle", Lookup::Triangle), ("bilinear", Lookup::Bilinear)]);
crate::choice!(Geodesic, "geodesic", [("arc", Geodesic::Arc), ("chord_sum", Geodesic::ChordSum)]);
crate::choice!(
    SamplingPath,
    "sampling",
    [("shared", SamplingPath::Shared), ("fast", SamplingPath::Fast), ("exact", SamplingPath::Exact)]
);
crate::choice!(Overlaps, "overlaps", [("keep", Overlaps::Keep), ("drop", Overlaps::Drop)]);
crate::choice!(Quadrature, "quadrature", [("pattern", Quadrature::Pattern), ("surfels", Quadrature::Surfels)]);
crate::choice!(Surface, "surface", [("smooth", Surface::Smooth), ("facets", Surface::Facets)]);
crate::choice!(
    GaussianMethod,
    "gaussian_method",
    [("moments", GaussianMethod::Moments), ("geodesic_area", GaussianMethod::GeodesicArea)]
);
crate::choice!(CurvatureMethod, "method", [("integral", CurvatureMethod::Integral), ("fit", CurvatureMethod::Fit)]);
crate::choice!(
    VolumeWeighting,
    "volume_weighting",
    [("distance", VolumeWeighting::Distance), ("uniform", VolumeWeighting::Uniform)]
);
crate::choice!(VertexQuery, "query", [("texture", VertexQuery::Texture), ("direct", VertexQuery::Direct)]);
crate::choice!(Precision, "precision", [("f32", Precision::F32), ("f16", Precision::F16)]);

/// The value of an option as the user writes it.
#[derive(Debug, Clone, PartialEq)]
pub enum OptionValue {
    /// A whole number (samples, resolutions, seeds, seam crossings).
    Count(u64),
    /// A number (lengths as fractions of `r`, tolerances).
    Number(f64),
    /// On or off.
    Flag(bool),
    /// One of the option's [`Choice`] names.
    Text(&'static str),
}

/// Every option of a computation with its value in `settings`, in a fixed order: the arguments
/// (`samples`, `compute_resolution`, `adaptive`, `seed`), then the options.
pub fn named_options(settings: &ComputeSettings) -> Vec<(&'static str, OptionValue)> {
    use OptionValue::{Count, Flag, Number, Text};
    vec![
        ("samples", Count(settings.samples as u64)),
        ("compute_resolution", Count(settings.resolution as u64)),
        ("adaptive", Flag(settings.adaptive)),
        ("seed", Count(settings.seed)),
        ("margin", Number(settings.margin)),
        ("grow_margin", Flag(settings.grow_margin)),
        ("max_jumps", Count(u64::from(settings.max_jumps))),
        ("relocation", Text(settings.relocation.name())),
        ("criterion", Text(settings.criterion.name())),
        ("lookup", Text(settings.lookup.name())),
        ("geodesic", Text(settings.geodesic.name())),
        ("sampling", Text(settings.sampling.name())),
        ("overlaps", Text(settings.overlaps.name())),
        ("quadrature", Text(settings.quadrature.name())),
        ("surface", Text(settings.surface.name())),
        ("gaussian_method", Text(settings.gaussian_method.name())),
        ("method", Text(settings.method.name())),
        ("volume_weighting", Text(settings.volume_weighting.name())),
        ("rho_min", Number(settings.rho_min_fraction)),
        ("flat_tol", Number(settings.flat_tol)),
        ("tau", Number(settings.tau)),
        ("standard_error", Flag(settings.standard_errors)),
    ]
}

/// The choices of every option that takes a name (the default first), `query` and `precision`
/// included.
pub fn option_choices() -> Vec<(&'static str, Vec<&'static str>)> {
    vec![
        (Relocation::OPTION, Relocation::names()),
        (Criterion::OPTION, Criterion::names()),
        (Lookup::OPTION, Lookup::names()),
        (Geodesic::OPTION, Geodesic::names()),
        (SamplingPath::OPTION, SamplingPath::names()),
        (Overlaps::OPTION, Overlaps::names()),
        (Quadrature::OPTION, Quadrature::names()),
        (Surface::OPTION, Surface::names()),
        (GaussianMethod::OPTION, GaussianMethod::names()),
        (CurvatureMethod::OPTION, CurvatureMethod::names()),
        (VolumeWeighting::OPTION, VolumeWeighting::names()),
        (VertexQuery::OPTION, VertexQuery::names()),
        (Precision::OPTION, Precision::names()),
    ]
}

/// A value the user gave for an option, before it is checked against the option.
#[derive(Debug, Clone, PartialEq)]
pub enum GivenValue {
    /// A number.
    Number(f64),
    /// On or off.
    Flag(bool),
    /// A name.
    Text(String),
}

impl ComputeSettings {
    /// Sets the option `name` to `value` (names as in [`named_options`]).
    ///
    /// # Errors
    /// [`UvfeatError::InvalidParameter`] for an unknown option (the message lists the valid ones),
    /// a value of the wrong kind, or a name that is not one of the option's choices. Ranges are
    /// checked by [`ComputeSettings::validate`].
    pub fn set_option(&mut self, name: &str, value: &GivenValue) -> Result<()> {
        let names: Vec<&'static str> = named_options(self).into_iter().map(|(n, _)| n).collect();
        let unknown = || UvfeatError::InvalidParameter {
            name: "options",
            reason: format!("unknown option {name:?}; valid: {names:?}"),
        };
        let option = *names.iter().find(|n| **n == name).ok_or_else(unknown)?;
        let wrong_kind = |expected: &str| UvfeatError::InvalidParameter {
            name: option,
            reason: format!("expects {expected}, got {value:?}"),
        };
        let number = || match *value {
            GivenValue::Number(x) => Ok(x),
            _ => Err(wrong_kind("a number")),
        };
        let count = || {
            number().and_then(|x| {
                if x.fract() == 0.0 && x >= 0.0 && x <= f64::from(u32::MAX) {
                    Ok(x as u64)
                } else {
                    Err(UvfeatError::InvalidParameter {
                        name: option,
                        reason: format!("must be a whole number >= 0, got {x}"),
                    })
                }
            })
        };
        let flag = || match *value {
            GivenValue::Flag(on) => Ok(on),
            _ => Err(wrong_kind("true or false")),
        };
        let text = || match value {
            GivenValue::Text(name) => Ok(name.as_str()),
            _ => Err(wrong_kind("a name")),
        };
        match option {
            "samples" => self.samples = count()? as usize,
            "compute_resolution" => self.resolution = count()? as usize,
            "adaptive" => self.adaptive = flag()?,
            "seed" => self.seed = count()?,
            "margin" => self.margin = number()?,
            "grow_margin" => self.grow_margin = flag()?,
            "max_jumps" => self.max_jumps = count()? as u32,
            "relocation" => self.relocation = Choice::named(text()?)?,
            "criterion" => self.criterion = Choice::named(text()?)?,
            "lookup" => self.lookup = Choice::named(text()?)?,
            "geodesic" => self.geodesic = Choice::named(text()?)?,
            "sampling" => self.sampling = Choice::named(text()?)?,
            "overlaps" => self.overlaps = Choice::named(text()?)?,
            "quadrature" => self.quadrature = Choice::named(text()?)?,
            "surface" => self.surface = Choice::named(text()?)?,
            "gaussian_method" => self.gaussian_method = Choice::named(text()?)?,
            "method" => self.method = Choice::named(text()?)?,
            "volume_weighting" => self.volume_weighting = Choice::named(text()?)?,
            "rho_min" => self.rho_min_fraction = number()?,
            "flat_tol" => self.flat_tol = number()?,
            "tau" => self.tau = number()?,
            "standard_error" => self.standard_errors = flag()?,
            _ => return Err(unknown()),
        }
        Ok(())
    }

    /// The paper's choices where they differ from ours (DESIGN.md §1.10): margin 1 without the
    /// coverage check, per-chart pattern repetition with one jump, bilinear lookup, geodesic-area
    /// K with chord-sum distances, uniform volume weighting. (Its f16 buffers belong to the atlas.)
    pub fn use_paper_choices(&mut self) {
        self.margin = 1.0;
        self.grow_margin = false;
        self.max_jumps = 1;
        self.relocation = Relocation::PerChart;
        self.lookup = Lookup::Bilinear;
        self.geodesic = Geodesic::ChordSum;
        self.gaussian_method = GaussianMethod::GeodesicArea;
        self.volume_weighting = VolumeWeighting::Uniform;
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::features::Feature;

    fn defaults() -> ComputeSettings {
        ComputeSettings::new(vec![Feature::MeanCurvature], 1.0)
    }

    #[test]
    fn every_named_option_round_trips_through_set_option() {
        let mut paper = defaults();
        paper.use_paper_choices();
        for source in [defaults(), paper] {
            let mut rebuilt = ComputeSettings::new(vec![Feature::MeanCurvature], 1.0);
            rebuilt.seed = 7;
            for (name, value) in named_options(&source) {
                let given = match value {
                    OptionValue::Count(n) => GivenValue::Number(n as f64),
                    OptionValue::Number(x) => GivenValue::Number(x),
                    OptionValue::Flag(on) => GivenValue::Flag(on),
                    OptionValue::Text(name) => GivenValue::Text(name.into()),
                };
                rebuilt.set_option(name, &given).unwrap();
            }
            assert_eq!(rebuilt, source);
        }
    }

    #[test]
    fn choices_list_the_default_first_and_names_round_trip() {
        for (option, names) in option_choices() {
            assert!(!names.is_empty(), "{option}");
        }
        fn default_first<T: Choice + Default>() -> bool {
            T::names()[0] == T::default().name()
        }
        assert!(default_first::<Relocation>() && default_first::<Criterion>() && default_first::<Lookup>());
        assert!(default_first::<Geodesic>() && default_first::<SamplingPath>() && default_first::<GaussianMethod>());
        assert!(default_first::<Overlaps>());
        assert!(default_first::<CurvatureMethod>() && default_first::<VolumeWeighting>());
        assert!(default_first::<VertexQuery>() && default_first::<Precision>());
        assert_eq!(SamplingPath::named("exact").unwrap(), SamplingPath::Exact);
        assert_eq!(VertexQuery::default().name(), "texture");
    }

    #[test]
    fn bad_options_are_named_errors() {
        let mut s = defaults();
        let message = |e: UvfeatError| e.to_string();
        assert!(message(s.set_option("margins", &GivenValue::Number(1.0)).unwrap_err()).contains("\"margin\""));
        assert!(message(s.set_option("lookup", &GivenValue::Text("nearest".into())).unwrap_err()).contains("bilinear"));
        assert!(message(s.set_option("margin", &GivenValue::Text("big".into())).unwrap_err()).contains("a number"));
        assert!(message(s.set_option("max_jumps", &GivenValue::Number(2.5)).unwrap_err()).contains("whole number"));
        assert!(message(s.set_option("adaptive", &GivenValue::Number(1.0)).unwrap_err()).contains("true or false"));
    }
}
