//! The data's point fields as the engine names them.

use tetray_mesh::ScalarField;

use crate::error::EngineError;

/// The name of the field added to data without fields (rendered as a
/// uniform volume, ParaView's Solid Color).
pub const SOLID: &str = "solid";

/// A field asked for that the data does not have, listing what it has.
pub(crate) fn unknown_field(name: &str, data: &str, fields: &[ScalarField]) -> EngineError {
    if fields.is_empty() {
        return EngineError::Options(format!("field {name:?}: {data} has no point scalar field"));
    }
    let names: Vec<String> = fields.iter().map(|f| format!("{:?}", f.name)).collect();
    EngineError::Options(format!(
        "field {name:?}: {data} has no such point field; it has {}",
        names.join(", ")
    ))
}
