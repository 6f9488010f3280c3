//! The ray-integration methods, by name.

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
