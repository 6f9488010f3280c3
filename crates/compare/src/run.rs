//! `compare` itself, for every front end: one view rendered by several
//! renderer / integrator / sort combinations through the engine, each timed
//! the same way ([`tetray_engine::measure`]) and measured against the exact
//! f64 CPU reference.

use tetray_engine::{Engine, RendererChoice, Setup, Timing, WalkOptions, measure};
use tetray_integrate::Method as Integrator;
use tetray_project::SortKind;

use crate::CompareError;
use crate::report::{Method, Report, Speed, compare};

/// One combination: a renderer, an integrator (`None`: the setup's) and,
/// for the projection, a visibility sort.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Spec {
    pub renderer: RendererChoice,
    pub method: Option<Integrator>,
    pub sort: Option<SortKind>,
}

/// A spec as `renderer[:integrator][:sort]` ("gpu", "project:exact:mpvo",
/// "shear-warp:riemann").
pub fn parse_spec(text: &str) -> Result<Spec, String> {
    let mut parts = text.trim().split(':');
    let renderer = match parts.next().map(str::parse::<RendererChoice>) {
        Some(Ok(renderer)) if renderer != RendererChoice::Auto => renderer,
        _ => {
            return Err(format!(
                "{text:?}: the renderer must be cpu, gpu, project or shear-warp"
            ));
        }
    };
    let mut spec = Spec {
        renderer,
        method: None,
        sort: None,
    };
    for part in parts {
        if let Ok(sort) = part.parse::<SortKind>() {
            if renderer != RendererChoice::Project || spec.sort.is_some() {
                return Err(format!("{text:?}: one sort, and only for project"));
            }
            spec.sort = Some(sort);
        } else if let Ok(method) = part.parse::<Integrator>() {
            if spec.method.replace(method).is_some() {
                return Err(format!("{text:?}: one integrator"));
            }
        } else {
            return Err(format!(
                "{text:?}: {part:?} is neither an integrator nor a sort (centroid, mpvo, mpvonc)"
            ));
        }
    }
    Ok(spec)
}

/// How [`run`] renders.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RunOptions {
    pub size: (u32, u32),
    /// Timed frames per combination; the median one is kept.
    pub frames: u32,
    /// The projection samples the transfer function adaptively.
    pub adaptive_tf: bool,
}

/// Renders the CPU f64 reference and every spec from the setup's camera
/// and compares them. The setup's integrator is left as it was.
pub fn run(
    setup: &mut Setup,
    specs: &[Spec],
    options: RunOptions,
    log: &dyn Fn(String),
) -> Result<Report, CompareError> {
    let original = setup.method;
    let result = (|| {
        let reference = Spec {
            renderer: RendererChoice::Cpu,
            method: Some(Integrator::Reference),
            sort: None,
        };
        let reference = render(setup, &reference, original, options, log)?;
        let methods = specs
            .iter()
            .map(|spec| render(setup, spec, original, options, log))
            .collect::<Result<Vec<_>, _>>()?;
        let title = format!("{} ({} tetrahedra)", setup.name(), setup.tet_count());
        compare(&title, reference, methods)
    })();
    setup.use_method(original)?;
    result
}

/// The frame of `spec` (`method`: the integrator of a spec that names
/// none).
fn render(
    setup: &mut Setup,
    spec: &Spec,
    method: Integrator,
    options: RunOptions,
    log: &dyn Fn(String),
) -> Result<Method, CompareError> {
    let method = spec.method.unwrap_or(method);
    setup.use_method(method)?;
    let setup: &Setup = setup;
    // No early termination: every method integrates every ray to its end,
    // as the reference does.
    let walk = WalkOptions {
        sort: spec.sort.unwrap_or(SortKind::Mpvonc),
        adaptive_tf: options.adaptive_tf,
        ..WalkOptions::default()
    };
    let engine = Engine::new(spec.renderer, setup, log)?;
    let label = match spec.renderer {
        RendererChoice::Project if !options.adaptive_tf => {
            format!("project {method} {} vertex-tf", walk.sort)
        }
        RendererChoice::Project => format!("project {method} {}", walk.sort),
        RendererChoice::ShearWarp => format!(
            "shear-warp {}",
            tetray_shearwarp::Classification::for_method(method).name()
        ),
        _ => format!("{} {method}", engine.name()),
    };
    let timing = Timing {
        frames: options.frames,
        orbit_step: 0.0,
        // GPU renderers compile their pipelines on the first frame.
        warm_up: !matches!(engine, Engine::Cpu | Engine::ShearWarp(_)),
    };
    let measured =
        measure(&engine, setup, &setup.camera, walk, options.size, timing).map_err(|e| {
            CompareError::Render {
                label: label.clone(),
                source: Box::new(e),
            }
        })?;
    let seconds = measured.median_seconds();
    log(format!(
        "{label}: {:.1} ms on {}",
        seconds * 1e3,
        engine.adapter()
    ));
    let frame = measured.median;
    Ok(Method {
        label,
        renderer: engine.name().to_string(),
        integrator: method.name().to_string(),
        sort: (spec.renderer == RendererChoice::Project).then(|| walk.sort.name().to_string()),
        adaptive_tf: frame.stats.project.map(|p| p.adaptive_tf),
        speed: Speed {
            ms_per_frame: seconds * 1e3,
            tets_per_s: setup.tet_count() as f64 / seconds,
            segments_per_s: frame.stats.counters.segments as f64 / seconds,
        },
        image: frame.image,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn specs_name_a_renderer_then_an_integrator_and_a_sort() {
        let spec = parse_spec("project:exact:mpvo").unwrap();
        assert_eq!(spec.renderer, RendererChoice::Project);
        assert_eq!(spec.method, Some(Integrator::Exact));
        assert_eq!(spec.sort, Some(SortKind::Mpvo));
        assert_eq!(parse_spec("gpu").unwrap().method, None);
        assert_eq!(
            parse_spec("project:centroid").unwrap().sort,
            Some(SortKind::Centroid)
        );
        assert!(parse_spec("gpu:mpvo").is_err(), "a sort is for project");
        assert!(parse_spec("auto").is_err());
        assert_eq!(
            parse_spec("shear-warp:riemann").unwrap().renderer,
            RendererChoice::ShearWarp
        );
        assert!(parse_spec("cpu:simpson").unwrap_err().contains("neither"));
        assert!(parse_spec("cpu:ppi:exact").is_err());
    }
}
