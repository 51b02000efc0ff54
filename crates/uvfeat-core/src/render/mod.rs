//! The 3D pictures (not a pipeline stage: it draws the outputs): per-vertex values on the mesh,
//! smooth-shaded by a z-buffer that rasterises the faces in bands of screen rows, and which side
//! of a closed mesh faces the viewer.

mod front_side;
mod screen;
mod shaded_view;

pub use front_side::front_side;
pub use screen::{rasterise_screen, ScreenFragments, NO_FACE};
pub use shaded_view::{shaded_view, ColourScale, Front, ViewFrame, AMBIENT};
