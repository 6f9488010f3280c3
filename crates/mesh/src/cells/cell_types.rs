//! VTK cell type ids: names and what the readers do with each.

/// What the reader does with a cell of a given VTK type.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum CellKind {
    Tetra,
    Voxel,
    Hexahedron,
    Wedge,
    Pyramid,
    /// Quadratic tetra (24) and Lagrange tetra of order 2 (71): 10 nodes.
    QuadraticTetra,
    /// Quadratic hexahedron (25): 20 nodes.
    QuadraticHexahedron,
    /// Triquadratic hexahedron (29): 27 nodes.
    TriquadraticHexahedron,
    /// Lagrange hexahedron of order 2 (72): 27 nodes, another edge order.
    LagrangeHexahedron,
    /// Quadratic wedge (26): 15 nodes.
    QuadraticWedge,
    /// Biquadratic-quadratic wedge (32) and Lagrange wedge of order 2
    /// (73): 18 nodes.
    BiquadraticWedge,
    /// Quadratic pyramid (27): 13 nodes.
    QuadraticPyramid,
    /// Pentagonal (15) and hexagonal (16) prisms.
    PentagonalPrism,
    HexagonalPrism,
    /// General polyhedron (42), with its faces listed apart.
    Polyhedron,
    /// 0-, 1- and 2-D cells (and the empty cell): skipped with a warning.
    LowerDim,
    /// 3-D cells that are not split (other higher-order cells, Bezier,
    /// convex point sets...).
    Unsupported3d,
    /// Not a VTK cell type id.
    Unknown,
}

impl CellKind {
    /// The number of points of the volume cells of fixed size.
    pub fn point_count(self) -> Option<usize> {
        match self {
            CellKind::Tetra => Some(4),
            CellKind::Pyramid => Some(5),
            CellKind::Wedge => Some(6),
            CellKind::Voxel | CellKind::Hexahedron => Some(8),
            CellKind::QuadraticTetra | CellKind::PentagonalPrism => Some(10),
            CellKind::HexagonalPrism => Some(12),
            CellKind::QuadraticPyramid => Some(13),
            CellKind::QuadraticWedge => Some(15),
            CellKind::BiquadraticWedge => Some(18),
            CellKind::QuadraticHexahedron => Some(20),
            CellKind::TriquadraticHexahedron | CellKind::LagrangeHexahedron => Some(27),
            _ => None,
        }
    }

    /// Quadratic and order-2 Lagrange cells, split through their nodes.
    pub fn is_higher_order(self) -> bool {
        matches!(
            self,
            CellKind::QuadraticTetra
                | CellKind::QuadraticHexahedron
                | CellKind::TriquadraticHexahedron
                | CellKind::LagrangeHexahedron
                | CellKind::QuadraticWedge
                | CellKind::BiquadraticWedge
                | CellKind::QuadraticPyramid
        )
    }
}

/// Classifies a VTK cell type id (vtkCellType.h).
pub fn classify(type_id: i64) -> CellKind {
    match type_id {
        10 => CellKind::Tetra,
        11 => CellKind::Voxel,
        12 => CellKind::Hexahedron,
        13 => CellKind::Wedge,
        14 => CellKind::Pyramid,
        15 => CellKind::PentagonalPrism,
        16 => CellKind::HexagonalPrism,
        24 | 71 => CellKind::QuadraticTetra,
        25 => CellKind::QuadraticHexahedron,
        26 => CellKind::QuadraticWedge,
        27 => CellKind::QuadraticPyramid,
        29 => CellKind::TriquadraticHexahedron,
        32 | 73 => CellKind::BiquadraticWedge,
        42 => CellKind::Polyhedron,
        72 => CellKind::LagrangeHexahedron,
        0..=9 | 21..=23 | 28 | 30 | 34..=36 | 51..=54 | 60..=63 | 68..=70 | 75..=77 => {
            CellKind::LowerDim
        }
        // 74, the Lagrange pyramid, has an id but no cell class in VTK, so
        // no node order to follow.
        31 | 33 | 37 | 41 | 55 | 56 | 64..=67 | 74 | 78..=81 => CellKind::Unsupported3d,
        _ => CellKind::Unknown,
    }
}

/// The VTK name of a cell type id, for messages.
pub fn type_name(type_id: i64) -> &'static str {
    match type_id {
        0 => "empty cell",
        1 => "vertex",
        2 => "poly-vertex",
        3 => "line",
        4 => "poly-line",
        5 => "triangle",
        6 => "triangle strip",
        7 => "polygon",
        8 => "pixel",
        9 => "quad",
        10 => "tetra",
        11 => "voxel",
        12 => "hexahedron",
        13 => "wedge",
        14 => "pyramid",
        15 => "pentagonal prism",
        16 => "hexagonal prism",
        21 => "quadratic edge",
        22 => "quadratic triangle",
        23 => "quadratic quad",
        24 => "quadratic tetra",
        25 => "quadratic hexahedron",
        26 => "quadratic wedge",
        27 => "quadratic pyramid",
        28 => "biquadratic quad",
        29 => "triquadratic hexahedron",
        30 => "quadratic-linear quad",
        31 => "quadratic-linear wedge",
        32 => "biquadratic-quadratic wedge",
        33 => "biquadratic-quadratic hexahedron",
        34 => "biquadratic triangle",
        35 => "cubic line",
        36 => "quadratic polygon",
        37 => "triquadratic pyramid",
        41 => "convex point set",
        42 => "polyhedron",
        51..=54 => "parametric curve/surface",
        55 | 56 => "parametric region",
        60..=63 => "higher-order curve/surface",
        64..=67 => "higher-order volume cell",
        68..=70 => "Lagrange curve/surface",
        71 => "Lagrange tetrahedron",
        72 => "Lagrange hexahedron",
        73 => "Lagrange wedge",
        74 => "Lagrange pyramid",
        75..=77 => "Bezier curve/surface",
        78 => "Bezier tetrahedron",
        79 => "Bezier hexahedron",
        80 => "Bezier wedge",
        81 => "Bezier pyramid",
        _ => "unknown type",
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn classification_covers_the_linear_cells() {
        assert_eq!(classify(10), CellKind::Tetra);
        assert_eq!(classify(12), CellKind::Hexahedron);
        assert_eq!(classify(5), CellKind::LowerDim);
        assert_eq!(classify(24), CellKind::QuadraticTetra);
        assert_eq!(classify(71), CellKind::QuadraticTetra);
        assert_eq!(classify(42), CellKind::Polyhedron);
        assert_eq!(classify(33), CellKind::Unsupported3d);
        assert_eq!(classify(74), CellKind::Unsupported3d);
        assert_eq!(classify(-1), CellKind::Unknown);
        assert_eq!(classify(200), CellKind::Unknown);
        assert_eq!(type_name(24), "quadratic tetra");
        assert_eq!(CellKind::Wedge.point_count(), Some(6));
    }
}
