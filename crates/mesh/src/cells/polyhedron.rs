//! Polyhedra (VTK type 42) and pentagonal/hexagonal prisms (15, 16): their
//! faces as the files give them, the closure check, and the conforming
//! split into tetrahedra.
//!
//! Split: a centroid point per cell (the mean of its vertices, fields
//! included) is joined to a triangulation of every face that both cells of
//! the face make alike from global ids alone: a triangle as is, a
//! quadrilateral cut through its smallest-index vertex (the rule `split.rs`
//! applies to hexahedra, wedges and pyramids, so a polyhedron conforms to
//! them too), a polygon of 5 or more vertices fanned from its centroid, a
//! point shared by the cells of the face (keyed by its vertex set). The
//! tets are oriented afterwards by the mesh loader; a polyhedron that is not
//! star-shaped from its centroid gives inverted tets that overlap, like any
//! such cell split this way.
//!
//! Face layouts (VTK's file formats):
//! - XML, before VTK 9.4: `faces` holds per polyhedron `nfaces`, then per
//!   face `npts id...`; `faceoffsets` the end of each cell's stream in
//!   `faces`, -1 for cells that are not polyhedra;
//! - XML, VTK 9.4 (file version 2.3): `face_connectivity` and
//!   `face_offsets` (end of each face) list the faces; `polyhedron_to_faces`
//!   and `polyhedron_offsets` (end of each cell) the faces of each cell;
//! - legacy: a polyhedron's CELLS entry is its face stream (`nfaces`, then
//!   `npts id...` per face) in place of a point list.

use std::collections::HashMap;

use super::added_points::{AddedPoints, mean_of};

/// Faces of the polyhedra of a grid, by cell index; point ids are global.
pub type PolyhedronFaces = HashMap<usize, Vec<Vec<i64>>>;

/// The faces of each polyhedron of a piece, by cell index in the piece.
pub type PieceFaces = Vec<(usize, Vec<Vec<i64>>)>;

/// The piece's cell index at fault and what is wrong.
pub type FaceError = (usize, String);

/// Parses one cell's face stream `nfaces, (npts, id...)*`, which must be
/// used up exactly.
pub fn parse_face_stream(stream: &[i64]) -> Result<Vec<Vec<i64>>, String> {
    let Some((&nfaces, mut rest)) = stream.split_first() else {
        return Err("its face stream is empty".into());
    };
    let nfaces = usize::try_from(nfaces)
        .ok()
        .filter(|&n| n < stream.len())
        .ok_or_else(|| format!("its face stream declares {nfaces} faces"))?;
    let mut faces = Vec::with_capacity(nfaces);
    for f in 0..nfaces {
        let npts = rest.first().and_then(|&n| usize::try_from(n).ok());
        let Some(npts) = npts.filter(|&n| n < rest.len()) else {
            return Err(format!(
                "face {f} of {nfaces} claims {:?} points but {} stream entries remain",
                rest.first(),
                rest.len().saturating_sub(1)
            ));
        };
        faces.push(rest[1..=npts].to_vec());
        rest = &rest[npts + 1..];
    }
    if !rest.is_empty() {
        return Err(format!(
            "{} entries follow its {nfaces} faces in its face stream",
            rest.len()
        ));
    }
    Ok(faces)
}

/// The faces of each polyhedron from `faces` + `faceoffsets` (pre-9.4
/// XML). `types` are the piece's cell types.
pub fn from_face_stream(
    faces: &[i64],
    faceoffsets: &[i64],
    types: &[i64],
) -> Result<PieceFaces, FaceError> {
    if faceoffsets.len() != types.len() {
        return Err((
            faceoffsets.len().min(types.len()),
            format!(
                "faceoffsets has {} entries for {} cells",
                faceoffsets.len(),
                types.len()
            ),
        ));
    }
    let mut out = Vec::new();
    let mut start = 0usize;
    for (c, (&end, &type_id)) in faceoffsets.iter().zip(types).enumerate() {
        if end < 0 {
            if type_id == 42 {
                return Err((c, "a polyhedron with no faces (faceoffsets is -1)".into()));
            }
            continue;
        }
        let end = usize::try_from(end).unwrap_or(usize::MAX);
        if end < start || end > faces.len() {
            return Err((
                c,
                format!(
                    "faceoffsets entry {end} is outside {start}..={} of the faces array",
                    faces.len()
                ),
            ));
        }
        if type_id == 42 {
            out.push((
                c,
                parse_face_stream(&faces[start..end]).map_err(|e| (c, e))?,
            ));
        }
        start = end;
    }
    Ok(out)
}

/// The faces of each polyhedron from the VTK 9.4 tables.
pub fn from_face_tables(
    face_connectivity: &[i64],
    face_offsets: &[i64],
    polyhedron_to_faces: &[i64],
    polyhedron_offsets: &[i64],
    types: &[i64],
) -> Result<PieceFaces, FaceError> {
    let range = |offsets: &[i64], i: usize, len: usize| -> Option<(usize, usize)> {
        let start = if i == 0 { 0 } else { offsets[i - 1] };
        let (start, end) = (
            usize::try_from(start).ok()?,
            usize::try_from(offsets[i]).ok()?,
        );
        (start <= end && end <= len).then_some((start, end))
    };
    if polyhedron_offsets.len() != types.len() {
        return Err((
            polyhedron_offsets.len().min(types.len()),
            format!(
                "polyhedron_offsets has {} entries for {} cells",
                polyhedron_offsets.len(),
                types.len()
            ),
        ));
    }
    let mut out = Vec::new();
    for (c, &type_id) in types.iter().enumerate() {
        let Some((a, b)) = range(polyhedron_offsets, c, polyhedron_to_faces.len()) else {
            return Err((c, "polyhedron_offsets entry out of range".into()));
        };
        if type_id != 42 {
            continue;
        }
        let mut faces = Vec::with_capacity(b - a);
        for &f in &polyhedron_to_faces[a..b] {
            let face = usize::try_from(f)
                .ok()
                .filter(|&f| f < face_offsets.len())
                .and_then(|f| range(face_offsets, f, face_connectivity.len()));
            let Some((s, e)) = face else {
                return Err((
                    c,
                    format!(
                        "face index {f} is out of range (there are {} faces)",
                        face_offsets.len()
                    ),
                ));
            };
            faces.push(face_connectivity[s..e].to_vec());
        }
        out.push((c, faces));
    }
    Ok(out)
}

/// The faces of a pentagonal (n = 5) or hexagonal (n = 6) prism: the base
/// 0..n, the top n..2n above it, the side quads; consistently oriented.
pub fn prism_faces(ids: &[u32], n: usize) -> Vec<Vec<u32>> {
    let mut faces = vec![
        (0..n).rev().map(|i| ids[i]).collect(),
        (n..2 * n).map(|i| ids[i]).collect(),
    ];
    for i in 0..n {
        let j = (i + 1) % n;
        faces.push(vec![ids[i], ids[j], ids[n + j], ids[n + i]]);
    }
    faces
}

/// Checks the faces close a volume: every face has 3 or more distinct
/// vertices, and every edge is used by exactly two faces, once in each
/// direction (so the orientations agree).
pub fn check_closed(faces: &[Vec<u32>]) -> Result<(), String> {
    if faces.len() < 4 {
        return Err(format!("{} faces cannot close a volume", faces.len()));
    }
    // Per undirected edge (low, high): uses low -> high, uses high -> low.
    let mut edges: HashMap<(u32, u32), (u32, u32)> = HashMap::new();
    for (f, face) in faces.iter().enumerate() {
        if face.len() < 3 {
            return Err(format!("face {f} has {} vertices", face.len()));
        }
        for (i, &a) in face.iter().enumerate() {
            if face[..i].contains(&a) {
                return Err(format!("face {f} repeats point {a}"));
            }
            let b = face[(i + 1) % face.len()];
            let entry = edges.entry((a.min(b), a.max(b))).or_insert((0, 0));
            if a < b {
                entry.0 += 1;
            } else {
                entry.1 += 1;
            }
        }
    }
    let mut bad: Vec<_> = edges.into_iter().filter(|&(_, u)| u != (1, 1)).collect();
    bad.sort_unstable();
    let Some(&((a, b), (up, down))) = bad.first() else {
        return Ok(());
    };
    Err(match up + down {
        1 => format!("the faces do not close: edge ({a}, {b}) belongs to one face only"),
        2 => format!(
            "the face orientations disagree: two faces run along edge ({a}, {b}) in the same direction"
        ),
        n => format!("edge ({a}, {b}) belongs to {n} faces"),
    })
}

/// Appends the tets of one polyhedron with the given faces (checked);
/// returns how many zero-volume tets of a collapsed cell were dropped.
pub fn split_polyhedron(
    faces: &[Vec<u32>],
    added: &mut AddedPoints,
    tets: &mut Vec<[u32; 4]>,
) -> usize {
    let mut vertices: Vec<u32> = faces.iter().flatten().copied().collect();
    vertices.sort_unstable();
    vertices.dedup();
    let centre = added.private(mean_of(&vertices));
    let mut dropped = 0;
    let mut push = |[a, b, c]: [u32; 3]| {
        if a == b || b == c || a == c {
            dropped += 1;
        } else {
            tets.push([centre, a, b, c]);
        }
    };
    for face in faces {
        match face.len() {
            3 => push([face[0], face[1], face[2]]),
            4 => {
                let k = (0..4).min_by_key(|&i| face[i]).unwrap_or(0);
                let at = |i: usize| face[(k + i) % 4];
                push([at(0), at(1), at(2)]);
                push([at(0), at(2), at(3)]);
            }
            n => {
                let middle = added.polygon_centroid(face);
                for i in 0..n {
                    push([middle, face[i], face[(i + 1) % n]]);
                }
            }
        }
    }
    dropped
}

#[cfg(test)]
mod tests {
    use super::*;

    fn cube_faces() -> Vec<Vec<u32>> {
        vec![
            vec![0, 3, 2, 1],
            vec![4, 5, 6, 7],
            vec![0, 1, 5, 4],
            vec![1, 2, 6, 5],
            vec![2, 3, 7, 6],
            vec![3, 0, 4, 7],
        ]
    }

    #[test]
    fn face_streams_parse_exactly() {
        let faces = parse_face_stream(&[2, 3, 0, 1, 2, 4, 0, 1, 2, 3]).unwrap();
        assert_eq!(faces, vec![vec![0, 1, 2], vec![0, 1, 2, 3]]);
        assert!(parse_face_stream(&[2, 3, 0, 1, 2]).is_err());
        assert!(parse_face_stream(&[1, 3, 0, 1, 2, 7]).is_err());
        assert!(parse_face_stream(&[]).is_err());
        assert!(parse_face_stream(&[-1]).is_err());
    }

    #[test]
    fn closure_check_names_the_open_or_flipped_edge() {
        assert_eq!(check_closed(&cube_faces()), Ok(()));
        let mut open = cube_faces();
        open.pop();
        let message = check_closed(&open).unwrap_err();
        assert!(message.contains("do not close"), "{message}");
        let mut flipped = cube_faces();
        flipped[0].reverse();
        let message = check_closed(&flipped).unwrap_err();
        assert!(message.contains("orientations disagree"), "{message}");
        for n in [5, 6] {
            let ids: Vec<u32> = (0..2 * n as u32).collect();
            assert_eq!(check_closed(&prism_faces(&ids, n)), Ok(()));
        }
    }

    #[test]
    fn cube_polyhedron_gives_two_tets_per_face() {
        let mut added = AddedPoints::new(8);
        let mut tets = Vec::new();
        assert_eq!(split_polyhedron(&cube_faces(), &mut added, &mut tets), 0);
        assert_eq!((tets.len(), added.len()), (12, 1));
        let mut prism = Vec::new();
        let ids: Vec<u32> = (0..10).collect();
        split_polyhedron(&prism_faces(&ids, 5), &mut added, &mut prism);
        // 2 pentagons fanned (5 each) and 5 quads (2 each); 3 more points.
        assert_eq!((prism.len(), added.len()), (20, 4));
    }
}
