//! The EnSight Gold reader on VTK's sample cases (as their writers made
//! them: C binary with steps in one file, every element type, a
//! rectilinear block) and on cases written by these tests, ASCII and C
//! binary, with a time set over `*` file names.

use std::path::{Path, PathBuf};

use tetray_io::{LoadOptions, load};

mod formats_common;

use formats_common::{at_step, field, scratch};

/// A file of VTK's EnSight samples.
fn ensight(name: &str) -> PathBuf {
    formats_common::data("real/ensight").join(name)
}

/// Counts from VTK 9.1's vtkGenericEnSightReader: LShape's hexa8 part has
/// 16 points and 3 cells, its four node-set parts 17, 4, 2 and 17 points
/// (one not in the hexahedra); elements' 16 cells are 8 volume cells and 8
/// points, bars, faces and an n-sided polygon; the block is 16 x 11 x 4.
#[test]
fn vtks_samples_read_with_vtks_counts() {
    let lshape = at_step(&ensight("LShape.case"), None);
    assert_eq!(lshape.report.format, "EnSight Gold");
    assert_eq!(lshape.report.cells_split, 3);
    assert_eq!(lshape.mesh.points.len(), 17);
    let times: Vec<f64> = (0..=10).map(|i| f64::from(i) / 10.0).collect();
    assert_eq!(lshape.report.times.len(), 11);
    for (t, want) in lshape.report.times.iter().zip(&times) {
        assert!((t - want).abs() < 1e-12, "{t}");
    }
    // The displacement starts at zero and grows.
    assert!(
        field(&lshape, "displacement_magnitude")
            .iter()
            .all(|&v| v == 0.0)
    );
    let last = at_step(&ensight("LShape.case"), Some(10));
    assert!(
        field(&last, "displacement_magnitude")
            .iter()
            .any(|&v| v > 0.0)
    );
    assert!(last.mesh.tets == lshape.mesh.tets);

    let elements = at_step(&ensight("elements.case"), None);
    // Seven split (the linear tetrahedron is not), 8 lower-dimensional
    // cells skipped.
    assert_eq!(elements.report.cells_split, 7);
    assert!(
        elements
            .report
            .warnings
            .iter()
            .any(|w| w.contains("skipped 8 lower-dimensional")),
        "{:?}",
        elements.report.warnings
    );
    for name in ["pointScalars", "pointVectors_magnitude", "cellScalars"] {
        field(&elements, name);
    }

    let block = at_step(&ensight("RectGrid_ascii.case"), None);
    assert_eq!(block.mesh.points.len(), 16 * 11 * 4);
    assert_eq!(block.report.cells_split, 15 * 10 * 3);
}

/// Writes EnSight items, ASCII or C binary.
struct Writer {
    binary: bool,
    bytes: Vec<u8>,
}

impl Writer {
    fn new(binary: bool) -> Writer {
        let mut w = Writer {
            binary,
            bytes: Vec::new(),
        };
        if binary {
            w.line("C Binary");
        }
        w
    }

    fn line(&mut self, text: &str) {
        if self.binary {
            let mut field = [0u8; 80];
            field[..text.len()].copy_from_slice(text.as_bytes());
            self.bytes.extend(field);
        } else {
            self.bytes.extend(format!("{text}\n").bytes());
        }
    }

    fn ints(&mut self, values: &[i32]) {
        for v in values {
            if self.binary {
                self.bytes.extend(v.to_le_bytes());
            } else {
                self.bytes.extend(format!("{v:10}\n").bytes());
            }
        }
    }

    fn floats(&mut self, values: &[f64]) {
        for &v in values {
            if self.binary {
                self.bytes.extend((v as f32).to_le_bytes());
            } else {
                self.bytes.extend(format!("{v:12.5e}\n").bytes());
            }
        }
    }
}

/// A unit cube of hexahedra (2 x 2 x 2, part 1, unstructured) beside a
/// uniform block (part 2, x from 1 to 2): f = x + 2y + 3z per node, times
/// the step's factor (1, then 2) in files `f.0000` and `f.0001`.
fn write_case(dir: &Path, binary: bool) {
    let mut geo = Writer::new(binary);
    geo.line("written by a test");
    geo.line("two parts");
    geo.line("node id off");
    geo.line("element id off");
    geo.line("part");
    geo.ints(&[1]);
    geo.line("hexahedra");
    geo.line("coordinates");
    let n = 3;
    let mut points = Vec::new();
    for k in 0..n {
        for j in 0..n {
            for i in 0..n {
                points.push([i as f64 * 0.5, j as f64 * 0.5, k as f64 * 0.5]);
            }
        }
    }
    geo.ints(&[points.len() as i32]);
    for axis in 0..3 {
        geo.floats(&points.iter().map(|p| p[axis]).collect::<Vec<_>>());
    }
    geo.line("hexa8");
    geo.ints(&[8]);
    let id = |i: usize, j: usize, k: usize| (i + n * (j + n * k) + 1) as i32;
    for k in 0..2 {
        for j in 0..2 {
            for i in 0..2 {
                geo.ints(&[
                    id(i, j, k),
                    id(i + 1, j, k),
                    id(i + 1, j + 1, k),
                    id(i, j + 1, k),
                    id(i, j, k + 1),
                    id(i + 1, j, k + 1),
                    id(i + 1, j + 1, k + 1),
                    id(i, j + 1, k + 1),
                ]);
            }
        }
    }
    geo.line("part");
    geo.ints(&[2]);
    geo.line("uniform block");
    geo.line("block uniform");
    geo.ints(&[3, 3, 3]);
    geo.floats(&[1.0, 0.0, 0.0, 0.5, 0.5, 0.5]);
    std::fs::write(dir.join("box.geo"), geo.bytes).unwrap();
    let block: Vec<[f64; 3]> = points.iter().map(|p| [p[0] + 1.0, p[1], p[2]]).collect();
    for (step, factor) in [(0, 1.0), (1, 2.0)] {
        let mut f = Writer::new(binary);
        f.line("f");
        for (part, pts) in [(1, &points), (2, &block)] {
            f.line("part");
            f.ints(&[part]);
            f.line(if part == 1 { "coordinates" } else { "block" });
            f.floats(
                &pts.iter()
                    .map(|p| factor * (p[0] + 2.0 * p[1] + 3.0 * p[2]))
                    .collect::<Vec<_>>(),
            );
        }
        std::fs::write(dir.join(format!("f.{step:04}")), f.bytes).unwrap();
    }
    let case = "FORMAT\ntype: ensight gold\n\nGEOMETRY\nmodel: box.geo\n\nVARIABLE\nscalar per node: 1 f f.****\n\n\
                TIME\ntime set: 1\nnumber of steps: 2\nfilename start number: 0\nfilename increment: 1\ntime values:\n0.0\n0.25\n";
    std::fs::write(dir.join("box.case"), case).unwrap();
}

/// The two parts weld on their shared face (9 points) into one box of
/// 16 hexahedra; f is exact at every point (quarters of small integers),
/// doubled at the second step, in ASCII and C binary alike.
#[test]
fn written_cases_weld_their_parts_and_follow_the_time_set() {
    for binary in [false, true] {
        let dir = scratch("ensight", if binary { "binary" } else { "ascii" });
        write_case(&dir, binary);
        let case = dir.join("box.case");
        for (step, factor) in [(0, 1.0f32), (1, 2.0)] {
            let loaded = at_step(&case, Some(step));
            assert_eq!(loaded.report.times, vec![0.0, 0.25]);
            assert_eq!(loaded.mesh.points.len(), 27 + 27 - 9, "binary {binary}");
            assert_eq!(loaded.report.cells_split, 16);
            assert_eq!(loaded.topology.components().0, 1, "the parts are welded");
            let origin = loaded.origin().as_vec3();
            for (p, v) in loaded.mesh.points.iter().zip(field(&loaded, "f")) {
                let q = *p + origin;
                let want = factor * (q.x + 2.0 * q.y + 3.0 * q.z);
                assert!(
                    (v - want).abs() < 1e-5,
                    "binary {binary} step {step} at {q}: {v} vs {want}"
                );
            }
        }
    }
}

/// Every prefix of the sample geometry files and of a written variable
/// file: an error naming the file, or (cut in trailing padding only) the
/// same mesh; never a panic.
#[test]
fn every_truncation_is_an_error_or_the_same_mesh() {
    let dir = scratch("ensight", "cut");
    for name in [
        "LShape.case",
        "LShape_geometry.geo",
        "LShape_displacement.var",
        "RectGrid_ascii.case",
        "RectGrid_ascii.geo",
        "RectGrid_ascii_pd_scalars",
        "RectGrid_ascii_pd_vectors",
    ] {
        std::fs::copy(ensight(name), dir.join(name)).unwrap();
    }
    for (case, file) in [
        ("LShape.case", "LShape_geometry.geo"),
        ("LShape.case", "LShape_displacement.var"),
        ("RectGrid_ascii.case", "RectGrid_ascii.geo"),
    ] {
        let bytes = std::fs::read(ensight(file)).unwrap();
        let want = at_step(&dir.join(case), None);
        for len in 0..bytes.len() {
            std::fs::write(dir.join(file), &bytes[..len]).unwrap();
            match load(&dir.join(case), &LoadOptions::default()) {
                Err(e) => assert!(
                    e.to_string().contains("ensight/cut"),
                    "{file} at {len}: {e}"
                ),
                Ok(m) => assert!(
                    m.mesh.tets == want.mesh.tets && m.mesh.fields == want.mesh.fields,
                    "{file} at {len}: read differently"
                ),
            }
        }
        std::fs::write(dir.join(file), &bytes).unwrap();
    }
}

/// Every byte of the C binary geometry overwritten in turn (0x00, 0xff, a
/// flipped bit): an error or a read, never a panic.
#[test]
fn every_corrupted_byte_is_an_error_or_a_read() {
    let dir = scratch("ensight", "corrupt");
    for name in [
        "LShape.case",
        "LShape_geometry.geo",
        "LShape_displacement.var",
    ] {
        std::fs::copy(ensight(name), dir.join(name)).unwrap();
    }
    let case = dir.join("LShape.case");
    for file in ["LShape_geometry.geo", "LShape_displacement.var"] {
        let bytes = std::fs::read(ensight(file)).unwrap();
        let mut copy = bytes.clone();
        for at in 0..bytes.len() {
            for value in [0x00, 0xff, bytes[at] ^ 0x01] {
                copy[at] = value;
                std::fs::write(dir.join(file), &copy).unwrap();
                if let Err(e) = load(&case, &LoadOptions::default()) {
                    assert!(
                        e.to_string().contains("ensight/corrupt"),
                        "{file} at {at}: {e}"
                    );
                }
            }
            copy[at] = bytes[at];
        }
        std::fs::write(dir.join(file), &bytes).unwrap();
    }
}
