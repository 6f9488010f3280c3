//! The defaults every front end shares (the CLI, Python, the viewer, the
//! distributed and in-situ renderers), written once.

/// Entries per side of the Psi table of partial pre-integration, as in
/// Moreland's *Fast High Accuracy Volume Rendering* (2004), section 5.2.4:
/// bilinear error about 1e-6 at this size.
pub const PSI_TABLE_SIZE: usize = 1024;

/// Entries per side of the full pre-integration table (Roettger and Engel):
/// one per scalar step of the table's range, front and back.
pub const PREINTEGRATION_TABLE_SIZE: usize = 256;

/// Azimuth and elevation (degrees) turned after the ResetCamera fit when no
/// camera value is given: an oblique view that shows a volume's depth (a
/// fit alone looks straight down -z and flattens it).
pub const DEFAULT_VIEW: (f32, f32) = (30.0, 20.0);

/// Full vertical view angle of a perspective camera, degrees (VTK's).
pub const VIEW_ANGLE: f32 = 30.0;

/// ParaView's default opacity unit distance (its ScalarOpacityUnitDistance):
/// the bounds diagonal over the cube root of the number of input cells, so
/// that an opacity means about the same per cell whatever the mesh's size;
/// the diagonal itself without cells, and 1 when that is not a positive
/// finite length.
pub fn unit_distance(diagonal: f64, cells: f64) -> f32 {
    let u = if cells > 0.0 {
        diagonal / cells.cbrt()
    } else {
        diagonal
    };
    if u > 0.0 && u.is_finite() {
        u as f32
    } else {
        1.0
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_unit_distance_is_the_diagonal_over_the_cube_root_of_the_cells() {
        assert_eq!(unit_distance(8.0, 8.0), 4.0);
        assert_eq!(unit_distance(3.0, 0.0), 3.0);
        assert_eq!(unit_distance(0.0, 10.0), 1.0);
        assert_eq!(unit_distance(f64::NAN, 10.0), 1.0);
    }
}
