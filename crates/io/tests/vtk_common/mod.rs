//! Helpers shared by the `vtk_*` integration tests.
#![allow(dead_code)]

use std::collections::HashMap;

use glam::Vec3;
use tetray_mesh::{ScalarField, TetMesh};

/// A small deterministic generator (64-bit LCG, high bits).
pub struct Lcg(pub u64);

impl Lcg {
    pub fn next_u32(&mut self) -> u32 {
        self.0 = self
            .0
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        (self.0 >> 32) as u32
    }

    /// A finite f32 drawn from all bit patterns (every exponent, subnormals).
    pub fn finite_f32(&mut self) -> f32 {
        loop {
            let x = f32::from_bits(self.next_u32());
            if x.is_finite() {
                return x;
            }
        }
    }

    pub fn below(&mut self, n: u32) -> u32 {
        self.next_u32() % n
    }
}

/// Values whose decimal or binary round trip is easy to get wrong.
pub const TRICKY: [f32; 10] = [
    0.0,
    -0.0,
    0.1,
    1.0 / 3.0,
    f32::MIN_POSITIVE,
    1e-45, // the smallest subnormal
    f32::MAX,
    -f32::MAX,
    16_777_217.0, // rounds to 2^24 + 2 in f32
    -123.456,
];

/// A mesh for round trips: tricky and random-bit coordinates and scalars,
/// random tetrahedra (writers and readers do not check geometry), two
/// fields whose names need escaping in both formats.
pub fn sample_mesh() -> TetMesh {
    let mut rng = Lcg(7);
    let n = 40;
    let mut coords: Vec<f32> = TRICKY.to_vec();
    while coords.len() < 3 * n {
        coords.push(rng.finite_f32());
    }
    let points = coords
        .chunks(3)
        .map(|c| Vec3::new(c[0], c[1], c[2]))
        .collect();
    let mut tets = Vec::new();
    for _ in 0..25 {
        let mut t = [0u32; 4];
        let mut k = 0;
        while k < 4 {
            let v = rng.below(n as u32);
            if !t[..k].contains(&v) {
                t[k] = v;
                k += 1;
            }
        }
        tets.push(t);
    }
    let field = |name: &str, rng: &mut Lcg| ScalarField {
        name: name.into(),
        values: (0..n)
            .map(|i| {
                if i < TRICKY.len() {
                    TRICKY[i]
                } else {
                    rng.finite_f32()
                }
            })
            .collect(),
    };
    let fields = vec![
        field("density", &mut rng),
        field("x velocity & <\"odd\">", &mut rng),
    ];
    TetMesh {
        points,
        tets,
        fields,
    }
}

/// Asserts two meshes are equal bit for bit (so -0.0 differs from 0.0).
pub fn assert_bit_exact(got: &TetMesh, want: &TetMesh, mode: &str) {
    let bits = |m: &TetMesh| -> Vec<u32> {
        m.points
            .iter()
            .flat_map(|p| p.to_array())
            .map(f32::to_bits)
            .collect()
    };
    assert_eq!(bits(got), bits(want), "{mode}: points");
    assert_eq!(got.tets, want.tets, "{mode}: tets");
    assert_eq!(got.fields.len(), want.fields.len(), "{mode}: field count");
    for (g, w) in got.fields.iter().zip(&want.fields) {
        assert_eq!(g.name, w.name, "{mode}: field name");
        let gb: Vec<u32> = g.values.iter().map(|v| v.to_bits()).collect();
        let wb: Vec<u32> = w.values.iter().map(|v| v.to_bits()).collect();
        assert_eq!(gb, wb, "{mode}: field {}", w.name);
    }
}

/// Six times the signed volume of tet `t`, in f64.
pub fn volume6(mesh: &TetMesh, t: [u32; 4]) -> f64 {
    let p = t.map(|i| mesh.points[i as usize].as_dvec3());
    (p[1] - p[0]).dot((p[2] - p[0]).cross(p[3] - p[0]))
}

/// How many tetrahedra hold each (sorted) triangle.
pub fn face_counts(tets: &[[u32; 4]]) -> HashMap<[u32; 3], usize> {
    let mut faces = HashMap::new();
    for t in tets {
        for skip in 0..4 {
            let mut f = [0u32; 3];
            let mut k = 0;
            for (i, &v) in t.iter().enumerate() {
                if i != skip {
                    f[k] = v;
                    k += 1;
                }
            }
            f.sort_unstable();
            *faces.entry(f).or_insert(0) += 1;
        }
    }
    faces
}

/// Asserts no triangle is shared by more than two tets and returns the
/// number of boundary triangles (held by one tet). A non-conforming split
/// of a shared quad leaves its four triangles on the boundary.
pub fn conforming_boundary(tets: &[[u32; 4]]) -> usize {
    let faces = face_counts(tets);
    assert!(
        faces.values().all(|&c| c <= 2),
        "a triangle in more than two tets"
    );
    faces.values().filter(|&&c| c == 1).count()
}
