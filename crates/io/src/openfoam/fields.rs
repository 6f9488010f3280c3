//! The fields of one time folder: every `volScalarField` and
//! `volVectorField` file's `internalField` (one value per cell, `uniform`
//! or `nonuniform`), as cell arrays. Boundary patches are not read: they
//! bound the volume, they do not fill it. Other files (surface fields such
//! as `phi`, point fields, folders) are passed over.

use std::path::Path;

use tetray_mesh::cells::CellArray;

use super::OpenFoamError;
use super::foam::FoamFile;

pub(super) fn read_fields(
    folder: &Path,
    ncells: usize,
    warnings: &mut Vec<String>,
) -> Result<Vec<CellArray>, OpenFoamError> {
    let mut names: Vec<(String, std::path::PathBuf)> = std::fs::read_dir(folder)
        .map_err(|source| OpenFoamError::Io {
            file: folder.display().to_string(),
            source,
        })?
        .filter_map(|e| e.ok())
        .map(|e| e.path())
        .filter(|p| p.is_file())
        .filter_map(|p| {
            let name = p.file_name()?.to_string_lossy().into_owned();
            let name = name.strip_suffix(".gz").unwrap_or(&name).to_string();
            (!name.starts_with('.') && !name.ends_with('~') && !name.ends_with(".orig"))
                .then_some((name, p))
        })
        .collect();
    names.sort();
    let mut out = Vec::new();
    for (name, path) in names {
        let (_, bytes) = super::read_maybe_gz(&path)?;
        // A file of the time folder that is not an OpenFOAM file (or is cut
        // short before its header ends) is an error, not a field lost.
        let file = FoamFile::parse(&bytes, &path.display().to_string())?;
        let width = match file.class.as_str() {
            "volScalarField" => 1,
            "volVectorField" => 3,
            "volSymmTensorField" | "volTensorField" | "volSphericalTensorField" => {
                warnings.push(format!("{name}: {} not read (tensor fields)", file.class));
                continue;
            }
            _ => continue,
        };
        let Some(values) = internal_field(&file, width, ncells, &name, warnings)? else {
            continue;
        };
        out.push(CellArray {
            name,
            components: width,
            values,
            section: format!("{} internalField", path.display()),
            defined: None,
        });
    }
    Ok(out)
}

/// The `internalField` entry: `uniform v`, `uniform (x y z)`, `uniform
/// $name` (a value the file defines above), or `nonuniform List<...> N
/// (...)` with N the cell count. `None`, with a warning, for a `$name`
/// defined elsewhere (an `#include`d file, which is not followed).
fn internal_field(
    file: &FoamFile,
    width: usize,
    ncells: usize,
    name: &str,
    warnings: &mut Vec<String>,
) -> Result<Option<Vec<f64>>, OpenFoamError> {
    let mut at = 0;
    if !file.seek_keyword(&mut at, "internalField") {
        return Err(file.invalid(file.body, "no internalField".into()));
    }
    let kind = file.word(&mut at);
    match kind.as_str() {
        "uniform" => {
            let mut p = at;
            file.skip_space(&mut p);
            let one = if file.bytes.get(p) == Some(&b'$') {
                let mut q = p + 1;
                let macro_name = file.word(&mut q);
                let mut def = 0;
                if !(file.seek_keyword(&mut def, &macro_name) && def < p) {
                    warnings.push(format!(
                        "{name}: internalField is ${macro_name}, defined outside the file \
                         (#include files are not followed): not read"
                    ));
                    return Ok(None);
                }
                file.ascii_item(&mut def, width, "internalField")?
            } else {
                file.ascii_item(&mut at, width, "internalField")?
            };
            Ok(Some(
                one.iter().copied().cycle().take(ncells * width).collect(),
            ))
        }
        "nonuniform" => {
            let list = file.word(&mut at);
            if !list.starts_with("List<") {
                return Err(file.invalid(at, format!("internalField: \"{list}\" is not a List")));
            }
            let values = file.numbers(&mut at, width, false, "internalField")?;
            if values.len() != ncells * width {
                return Err(file.invalid(
                    at,
                    format!(
                        "internalField holds {} values, the mesh has {ncells} cells",
                        values.len() / width
                    ),
                ));
            }
            Ok(Some(values))
        }
        other => Err(file.invalid(
            at,
            format!("internalField \"{other}\": expected uniform or nonuniform"),
        )),
    }
}
