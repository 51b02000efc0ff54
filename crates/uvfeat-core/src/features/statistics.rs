//! One pass over a neighbourhood's samples collects every weighted sum the estimators need
//! (several features from one pass), plus what the adaptive sampler needs for standard errors.

use crate::sampling::Sample;

/// Weighted sums of one integrand `g` with weights `w`.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct WeightedSums {
    /// `sum w`.
    pub w: f64,
    /// `sum w^2`.
    pub w2: f64,
    /// `sum w g`.
    pub wg: f64,
    /// `sum w g^2`.
    pub wg2: f64,
}

impl WeightedSums {
    /// Adds one sample of the integrand `g` with weight `w`.
    #[inline]
    pub fn add(&mut self, w: f64, g: f64) {
        self.w += w;
        self.w2 += w * w;
        self.wg += w * g;
        self.wg2 += w * g * g;
    }

    /// Adds a piece of surface whose weight `w` and `sum w g` are summed over it (exactly where
    /// the integrand is linear in the position) and `sum w g^2` given as read at its centroid.
    #[inline]
    pub fn add_parts(&mut self, w: f64, wg: f64, wg2: f64) {
        self.w += w;
        self.w2 += w * w;
        self.wg += wg;
        self.wg2 += wg2;
    }

    fn merge(&mut self, other: &Self) {
        self.w += other.w;
        self.w2 += other.w2;
        self.wg += other.wg;
        self.wg2 += other.wg2;
    }

    /// Weighted mean `<g>_w` (NaN without samples: never a silent 0).
    pub fn mean(&self) -> f64 {
        if self.w > 0.0 {
            self.wg / self.w
        } else {
            f64::NAN
        }
    }

    /// Weighted mean of `g^2`.
    pub fn mean_square(&self) -> f64 {
        if self.w > 0.0 {
            self.wg2 / self.w
        } else {
            f64::NAN
        }
    }

    /// Weighted variance `<g^2> - <g>^2` (clamped at 0 against rounding).
    pub fn variance(&self) -> f64 {
        (self.mean_square() - self.mean().powi(2)).max(0.0)
    }

    /// Monte Carlo standard error of the mean: `sqrt(Var_w(g) / N_eff)`, `N_eff = (sum w)^2 / sum w^2`.
    pub fn standard_error(&self) -> f64 {
        if self.w2 > 0.0 {
            (self.variance() * self.w2 / (self.w * self.w)).sqrt()
        } else {
            f64::NAN
        }
    }
}

/// How the sphere-volume integrands weight samples (DESIGN.md §2.2, decision A2).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum VolumeWeighting {
    /// `w = dA rho`: consistent for area-uniform samples (default).
    #[default]
    Distance,
    /// `w = 1`: the paper's literal estimator, biased to `8H/9` (reproduction only).
    Uniform,
}

/// Sums over one neighbourhood, one [`WeightedSums`] per integrand.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct NeighbourhoodStats {
    /// `g = sin(alpha)` with the volume weighting (mean curvature, sphere volumes).
    pub elevation: WeightedSums,
    /// `g = rho / r` with the volume weighting: the pattern's empirical radial moment.
    pub radial: WeightedSums,
    /// `g = |n - n_i|^2 / rho^2`, `w = dA`, `rho >= rho_min` (bending energy).
    pub bending: WeightedSums,
    /// `g = k_i = -2 sin(alpha)/rho`, `w = dA (rho/r)^2`, `rho >= rho_min` (curvature moments).
    pub normal_curvature: WeightedSums,
    /// `g = [d_i < r]`, `w = dA`, all samples (geodesic-disk area: `GA = wg`).
    pub geodesic_disk: WeightedSums,
}

/// What the statistics depend on besides the samples.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct StatsSettings {
    /// Neighbourhood radius `r`.
    pub radius: f64,
    /// Inner exclusion `rho_min` of the bending and moment integrands (DESIGN.md §1.10: `0.1 r`).
    pub rho_min: f64,
    /// Weighting of the volume integrands.
    pub volume_weighting: VolumeWeighting,
}

impl NeighbourhoodStats {
    /// Accumulates the samples of a neighbourhood whose centre has normal `normal`.
    pub fn accumulate(&mut self, samples: &[Sample], normal: glam::DVec3, settings: &StatsSettings) {
        // One division per sample: the others are products with these (rounding aside, the same).
        let inverse_radius = 1.0 / settings.radius;
        let inverse_radius2 = inverse_radius * inverse_radius;
        for s in samples {
            let w = match settings.volume_weighting {
                VolumeWeighting::Distance => s.area * s.distance,
                VolumeWeighting::Uniform => 1.0,
            };
            self.elevation.add(w, s.sin_alpha);
            self.radial.add(w, s.distance * inverse_radius);
            let inside = s.geodesic < settings.radius;
            self.geodesic_disk.add(s.area, if inside { 1.0 } else { 0.0 });
            if s.distance >= settings.rho_min {
                let inv_rho2 = 1.0 / (s.distance * s.distance);
                self.bending.add(s.area, (normal - s.normal).length_squared() * inv_rho2);
                // On a triangle mesh a sample sits on a flat facet, off the smooth surface by about
                // h^2 k / 8, which moves k_i by 2 (h^2 k / 8) / rho^2: the samples near p would
                // dominate Var(k) and bias K_m = H^2 - 2 Var low. Weighting by rho^2 keeps the
                // estimator consistent (any radial weight does, DESIGN.md §2.5b) and removes that bias
                // (measured: unit sphere |K-1| 0.032 -> 0.012, torus outer K -20 % -> -5 %).
                let w = s.area * s.distance * s.distance * inverse_radius2;
                self.normal_curvature.add(w, -2.0 * s.sin_alpha * s.distance * inv_rho2);
            }
        }
    }

    /// Rescales the absolute areas (used by the geodesic-disk area) by `factor`, e.g. `1/2` after
    /// pooling two half-size stages whose samples each stood for `A_uv / (N/2)`.
    pub fn scale_areas(&mut self, factor: f64) {
        let d = &mut self.geodesic_disk;
        d.w *= factor;
        d.wg *= factor;
        d.w2 *= factor * factor;
        d.wg2 *= factor * factor;
    }

    /// Pools another stage's statistics.
    pub fn merge(&mut self, other: &Self) {
        self.elevation.merge(&other.elevation);
        self.radial.merge(&other.radial);
        self.bending.merge(&other.bending);
        self.normal_curvature.merge(&other.normal_curvature);
        self.geodesic_disk.merge(&other.geodesic_disk);
    }
}
