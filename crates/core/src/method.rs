//! The ray-integration methods, by name, and which renderers run each: the
//! one table the CPU ray caster, the GPU kernels (their `METHOD_*`
//! constants are generated from it, see [`wgsl_constants`]), the cell
//! projection and shear-warp consult.

use std::fmt;
use std::str::FromStr;

/// Which optical model a method integrates (or approximates).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Model {
    /// Luminance and attenuation linear along each piece (section 5.2).
    LinearAttenuation,
    /// Luminance and opacity linear along each piece (section 5.3).
    LinearOpacity,
}

/// A method of integrating a ray segment.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Method {
    /// Averaged luminance and attenuation (Shirley-Tuchman, VTK's
    /// homogeneous integrator), eq. 3.16.
    Average,
    /// Averaged luminance and opacity (Wilhelms-van Gelder).
    AverageOpacity,
    /// Linear luminance and attenuation in closed form (Williams-Max-Stein),
    /// eq. 3.28, in f64.
    Exact,
    /// Partial pre-integration with the Psi table, eq. 5.5 (the default).
    Ppi,
    /// Linear luminance, average opacity (section 5.3.1).
    LinAvgOpacity,
    /// Linear luminance and opacity, improved approximation (section 5.3.2).
    LinOpacity,
    /// Full pre-integration (Roettger/Engel): a table over (s_front, s_back)
    /// for one transfer function and length, corrected for other lengths.
    Preintegrated,
    /// Riemann sum of homogeneous steps (eq. 3.13).
    Riemann,
    /// f64 adaptive quadrature of the linear-attenuation model.
    Reference,
    /// f64 adaptive quadrature of the linear-opacity model.
    ReferenceOpacity,
}

impl Method {
    /// Every method, in the order the CLI lists them.
    pub const ALL: [Method; 10] = [
        Method::Ppi,
        Method::Exact,
        Method::Average,
        Method::AverageOpacity,
        Method::LinAvgOpacity,
        Method::LinOpacity,
        Method::Preintegrated,
        Method::Riemann,
        Method::Reference,
        Method::ReferenceOpacity,
    ];

    /// The name used on the command line.
    pub fn name(self) -> &'static str {
        match self {
            Method::Average => "average",
            Method::AverageOpacity => "average-opacity",
            Method::Exact => "exact",
            Method::Ppi => "ppi",
            Method::LinAvgOpacity => "lin-avg-opacity",
            Method::LinOpacity => "lin-opacity",
            Method::Preintegrated => "preintegrated",
            Method::Riemann => "riemann",
            Method::Reference => "reference",
            Method::ReferenceOpacity => "reference-opacity",
        }
    }

    /// The optical model this method integrates.
    pub fn model(self) -> Model {
        match self {
            Method::AverageOpacity
            | Method::LinAvgOpacity
            | Method::LinOpacity
            | Method::ReferenceOpacity => Model::LinearOpacity,
            _ => Model::LinearAttenuation,
        }
    }

    /// The f64 reference of this method's model.
    pub fn reference(self) -> Method {
        match self.model() {
            Model::LinearAttenuation => Method::Reference,
            Model::LinearOpacity => Method::ReferenceOpacity,
        }
    }

    /// Whether segments are cut at transfer-function knots before this
    /// method integrates them (the table and sampling methods see the
    /// transfer function themselves).
    pub fn splits_at_knots(self) -> bool {
        !matches!(self, Method::Preintegrated | Method::Riemann)
    }

    /// Comma-separated names, for error messages.
    pub fn names() -> String {
        Method::ALL.map(Method::name).join(", ")
    }

    /// The GPU kernels' code of this method (WGSL `METHOD_*`, shared by the
    /// ray-casting kernel and the cell projection), or `None` for the f64
    /// references, which run on the CPU only.
    pub fn gpu_code(self) -> Option<u32> {
        GPU_METHODS
            .iter()
            .position(|&(m, _)| m == self)
            .map(|code| code as u32)
    }

    /// Whether the GPU ray caster and the cell projection can integrate
    /// with this method.
    pub fn has_gpu_kernel(self) -> bool {
        self.gpu_code().is_some()
    }

    /// The method a GPU renderer shows in place of this one: itself, or for
    /// an f64 reference the closed form of the same optical model (the
    /// viewer's previews of a CPU reference frame).
    pub fn gpu_stand_in(self) -> Method {
        match self {
            Method::Reference => Method::Exact,
            Method::ReferenceOpacity => Method::LinOpacity,
            other => other,
        }
    }

    /// The methods the GPU renderers run, by name.
    pub fn gpu_names() -> String {
        GPU_METHODS.map(|(m, _)| m.name()).join(", ")
    }
}

/// The methods with a GPU kernel, in the order of their codes, with the
/// name of their WGSL constant.
const GPU_METHODS: [(Method, &str); 8] = [
    (Method::Ppi, "METHOD_PPI"),
    (Method::Exact, "METHOD_EXACT"),
    (Method::Average, "METHOD_AVERAGE"),
    (Method::AverageOpacity, "METHOD_AVERAGE_OPACITY"),
    (Method::LinAvgOpacity, "METHOD_LIN_AVG_OPACITY"),
    (Method::LinOpacity, "METHOD_LIN_OPACITY"),
    (Method::Preintegrated, "METHOD_PREINTEGRATED"),
    (Method::Riemann, "METHOD_RIEMANN"),
];

/// The WGSL declarations of the method codes (`const METHOD_PPI: u32 =
/// 0u;` ...), put in front of every kernel that integrates, so the shaders
/// and [`Method::gpu_code`] cannot disagree.
pub fn wgsl_constants() -> String {
    GPU_METHODS
        .iter()
        .enumerate()
        .map(|(code, (method, name))| format!("// {method}\nconst {name}: u32 = {code}u;\n"))
        .collect()
}

impl fmt::Display for Method {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

/// An unknown method name.
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
#[error("unknown integrator {name:?}; expected one of: {expected}")]
pub struct UnknownMethod {
    pub name: String,
    pub expected: String,
}

impl FromStr for Method {
    type Err = UnknownMethod;

    fn from_str(text: &str) -> Result<Self, Self::Err> {
        let lower = text.trim().to_ascii_lowercase();
        let alias = match lower.as_str() {
            "psi" | "partial" | "partial-preintegration" => Some(Method::Ppi),
            "wms" | "williams-max-stein" | "linear" => Some(Method::Exact),
            "homogeneous" | "avg" => Some(Method::Average),
            "full-preintegration" | "preintegration" => Some(Method::Preintegrated),
            _ => None,
        };
        alias
            .or_else(|| Method::ALL.into_iter().find(|m| m.name() == lower))
            .ok_or_else(|| UnknownMethod {
                name: text.to_string(),
                expected: Method::names(),
            })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_method_but_the_references_has_a_distinct_gpu_code() {
        let codes: Vec<Option<u32>> = Method::ALL.iter().map(|m| m.gpu_code()).collect();
        for (method, code) in Method::ALL.iter().zip(&codes) {
            let reference = matches!(method, Method::Reference | Method::ReferenceOpacity);
            assert_eq!(code.is_none(), reference, "{method}");
            assert!(method.gpu_stand_in().has_gpu_kernel(), "{method}");
            assert_eq!(method.gpu_stand_in().model(), method.model(), "{method}");
        }
        let mut known: Vec<u32> = codes.into_iter().flatten().collect();
        known.sort_unstable();
        assert_eq!(known, (0..8).collect::<Vec<_>>());
    }

    #[test]
    fn the_wgsl_constants_carry_the_codes() {
        let wgsl = wgsl_constants();
        assert!(wgsl.contains("const METHOD_PPI: u32 = 0u;"), "{wgsl}");
        assert!(wgsl.contains("const METHOD_RIEMANN: u32 = 7u;"), "{wgsl}");
        assert_eq!(wgsl.matches("const ").count(), 8);
    }
}
