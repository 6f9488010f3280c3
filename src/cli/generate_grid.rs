//! `tetray generate grid`: a uniform grid over [-1, 1]^3 with the analytic
//! point scalar "bump" (a Gaussian with a ripple), written as a `.vti`
//! ImageData with raw appended Float32 data. Every renderer reads it: the
//! tetrahedral ones split it into 5 tetrahedra per cell, `--renderer
//! shear-warp` renders it as the grid it is.

use std::io::Write;
use std::path::PathBuf;
use std::time::Instant;

use anyhow::{Context, bail};
use clap::Args;
use rayon::prelude::*;
use serde::Serialize;

/// `tetray generate grid`.
#[derive(Debug, Clone, Args)]
pub struct GridArgs {
    /// Points along x, y and z (each at least 2).
    #[arg(long, value_name = "NX,NY,NZ", value_delimiter = ',', default_values_t = [64usize, 64, 64])]
    pub dims: Vec<usize>,
    /// Output file (.vti).
    #[arg(short, long, value_name = "FILE")]
    pub output: PathBuf,
}

#[derive(Debug, Serialize)]
struct GridJson {
    kind: &'static str,
    path: String,
    dims: [usize; 3],
    origin: [f64; 3],
    spacing: [f64; 3],
    field: &'static str,
    points: usize,
    bytes: u64,
    seconds: f64,
}

/// The analytic field at `(x, y, z)` in [-1, 1]^3.
pub fn bump(x: f64, y: f64, z: f64) -> f32 {
    let r2 = x * x + y * y + z * z;
    ((-2.5 * r2).exp() + 0.15 * (5.0 * x).sin() * (4.0 * y).cos()) as f32
}

pub fn grid(args: &GridArgs) -> anyhow::Result<()> {
    let start = Instant::now();
    let dims: [usize; 3] = match args.dims[..] {
        [a, b, c] if a >= 2 && b >= 2 && c >= 2 => [a, b, c],
        _ => bail!("--dims {:?}: three counts of 2 or more", args.dims),
    };
    let points = dims
        .iter()
        .try_fold(1usize, |n, &d| n.checked_mul(d))
        .filter(|&n| n <= 1 << 31)
        .with_context(|| format!("--dims {dims:?}: more than 2^31 points"))?;
    if args.output.extension().and_then(|e| e.to_str()) != Some("vti") {
        bail!(
            "--output {}: the file must end in .vti",
            args.output.display()
        );
    }
    let spacing = dims.map(|n| 2.0 / (n - 1) as f64);
    let origin = [-1.0; 3];
    let bytes: Vec<u8> = (0..points)
        .into_par_iter()
        .flat_map_iter(|p| {
            let (i, j, k) = (
                p % dims[0],
                (p / dims[0]) % dims[1],
                p / (dims[0] * dims[1]),
            );
            let at = |a: usize, n: usize| origin[a] + spacing[a] * n as f64;
            bump(at(0, i), at(1, j), at(2, k)).to_le_bytes()
        })
        .collect();
    let extent = format!("0 {} 0 {} 0 {}", dims[0] - 1, dims[1] - 1, dims[2] - 1);
    let header = format!(
        "<?xml version=\"1.0\"?>\n\
         <VTKFile type=\"ImageData\" version=\"1.0\" byte_order=\"LittleEndian\" header_type=\"UInt64\">\n\
         \x20 <ImageData WholeExtent=\"{extent}\" Origin=\"{} {} {}\" Spacing=\"{} {} {}\">\n\
         \x20   <Piece Extent=\"{extent}\">\n\
         \x20     <PointData Scalars=\"bump\">\n\
         \x20       <DataArray type=\"Float32\" Name=\"bump\" format=\"appended\" offset=\"0\"/>\n\
         \x20     </PointData>\n\
         \x20   </Piece>\n\
         \x20 </ImageData>\n\
         \x20 <AppendedData encoding=\"raw\">\n   _",
        origin[0], origin[1], origin[2], spacing[0], spacing[1], spacing[2]
    );
    let write = || -> std::io::Result<()> {
        let mut file = std::io::BufWriter::new(std::fs::File::create(&args.output)?);
        file.write_all(header.as_bytes())?;
        file.write_all(&(bytes.len() as u64).to_le_bytes())?;
        file.write_all(&bytes)?;
        file.write_all(b"\n  </AppendedData>\n</VTKFile>\n")?;
        file.flush()
    };
    write().with_context(|| format!("--output {}: cannot write", args.output.display()))?;
    let json = GridJson {
        kind: "grid",
        path: args.output.display().to_string(),
        dims,
        origin,
        spacing,
        field: "bump",
        points,
        bytes: std::fs::metadata(&args.output).map_or(0, |m| m.len()),
        seconds: start.elapsed().as_secs_f64(),
    };
    println!("{}", serde_json::to_string_pretty(&json)?);
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn written_grids_read_back_as_images() {
        let dir = std::env::temp_dir().join(format!("tetray-generate-grid-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let output = dir.join("g.vti");
        grid(&GridArgs {
            dims: vec![4, 3, 2],
            output: output.clone(),
        })
        .unwrap();
        let image = tetray_io::vtk::read_image_grid(&output).unwrap();
        assert_eq!(image.dims, [4, 3, 2]);
        assert_eq!(image.origin, [-1.0; 3]);
        assert_eq!(image.spacing, [2.0 / 3.0, 1.0, 2.0]);
        assert_eq!(image.fields[0].name, "bump");
        assert_eq!(image.fields[0].values[23], bump(1.0, 1.0, 1.0));
        let bad = GridArgs {
            dims: vec![1, 3, 2],
            output,
        };
        assert!(grid(&bad).is_err());
        std::fs::remove_dir_all(&dir).unwrap();
    }
}
