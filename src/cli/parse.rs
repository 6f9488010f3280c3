//! The parsers of the commands' option values. Each rejects what cannot be
//! used (non-finite numbers, zero sizes, unknown names), naming the
//! problem, so a bad value fails before any work starts.

use glam::{DVec3, Vec3};
use tetray_boundary_bvh::BuildPreset;
use tetray_integrate::Method;
use tetray_project::SortKind;

/// An integration method by name (see [`Method::names`]).
pub fn parse_method(text: &str) -> Result<Method, String> {
    text.parse()
        .map_err(|e: tetray_integrate::UnknownMethod| e.to_string())
}

/// A visibility sort by name.
pub fn parse_sort(text: &str) -> Result<SortKind, String> {
    text.parse()
        .map_err(|e: tetray_project::sort::UnknownSort| e.to_string())
}

pub fn parse_bvh_preset(text: &str) -> Result<BuildPreset, String> {
    text.parse()
        .map_err(|e: tetray_boundary_bvh::BvhError| e.to_string())
}

/// `x,y,z`.
/// `min,max` with min < max.
pub fn parse_range(text: &str) -> Result<(f32, f32), String> {
    match parse_floats(text)?.as_slice() {
        [lo, hi] if lo < hi => Ok((*lo, *hi)),
        [_, _] => Err(format!(
            "{text:?}: the first number must be below the second"
        )),
        _ => Err(format!("expected two numbers min,max, got {text:?}")),
    }
}

pub fn parse_vec3(text: &str) -> Result<Vec3, String> {
    match parse_floats(text)?.as_slice() {
        [x, y, z] => Ok(Vec3::new(*x, *y, *z)),
        _ => Err(format!("expected three numbers x,y,z, got {text:?}")),
    }
}

/// `x,y,z` in f64 (positions in a file's coordinates, which may be far
/// from zero).
pub fn parse_dvec3(text: &str) -> Result<DVec3, String> {
    let parts: Vec<f64> = text
        .split(',')
        .map(|part| match part.trim().parse::<f64>() {
            Ok(v) if v.is_finite() => Ok(v),
            Ok(v) => Err(format!("{v} is not finite in {text:?}")),
            Err(_) => Err(format!("{:?} is not a number in {text:?}", part.trim())),
        })
        .collect::<Result<_, _>>()?;
    match parts.as_slice() {
        [x, y, z] => Ok(DVec3::new(*x, *y, *z)),
        _ => Err(format!("expected three numbers x,y,z, got {text:?}")),
    }
}

/// `r,g,b` or one value for all three channels, each finite and >= 0.
pub fn parse_rgb(text: &str) -> Result<Vec3, String> {
    let rgb = match parse_floats(text)?.as_slice() {
        [v] => Vec3::splat(*v),
        [r, g, b] => Vec3::new(*r, *g, *b),
        _ => return Err(format!("expected r,g,b or a single value, got {text:?}")),
    };
    if rgb.min_element() < 0.0 {
        return Err(format!("{text:?} has a negative value"));
    }
    Ok(rgb)
}

/// `WxH`, each side in 1..=16384.
pub fn parse_size(text: &str) -> Result<(u32, u32), String> {
    let (w, h) = text
        .split_once(['x', 'X'])
        .ok_or_else(|| format!("expected WxH (e.g. 512x512), got {text:?}"))?;
    let side = |s: &str| {
        s.trim()
            .parse::<u32>()
            .ok()
            .filter(|v| (1..=16384).contains(v))
            .ok_or_else(|| format!("{text:?}: each side must be a whole number in 1..=16384"))
    };
    Ok((side(w)?, side(h)?))
}

/// A finite number.
pub fn parse_finite(text: &str) -> Result<f32, String> {
    match parse_floats(text)?.as_slice() {
        [v] => Ok(*v),
        _ => Err(format!("expected one number, got {text:?}")),
    }
}

/// A finite simulation time.
pub fn parse_time(text: &str) -> Result<f64, String> {
    match text.trim().parse::<f64>() {
        Ok(t) if t.is_finite() => Ok(t),
        _ => Err(format!("expected a finite number, got {text:?}")),
    }
}

/// A finite number > 0.
pub fn parse_positive(text: &str) -> Result<f32, String> {
    let v = parse_finite(text)?;
    if v > 0.0 {
        Ok(v)
    } else {
        Err(format!("{v} must be greater than 0"))
    }
}

/// A finite number >= 0.
pub fn parse_non_negative(text: &str) -> Result<f32, String> {
    let v = parse_finite(text)?;
    if v >= 0.0 {
        Ok(v)
    } else {
        Err(format!("{v} must not be negative"))
    }
}

/// A number in [0, 1].
pub fn parse_unit_interval(text: &str) -> Result<f32, String> {
    let v = parse_finite(text)?;
    if (0.0..=1.0).contains(&v) {
        Ok(v)
    } else {
        Err(format!("{v} is outside [0, 1]"))
    }
}

pub fn parse_view_angle(text: &str) -> Result<f32, String> {
    let v = parse_finite(text)?;
    if v > 0.0 && v < 180.0 {
        Ok(v)
    } else {
        Err(format!("{v} degrees is outside (0, 180)"))
    }
}

pub fn parse_early_termination(text: &str) -> Result<f32, String> {
    let v = parse_finite(text)?;
    if v > 0.0 && v <= 1.0 {
        Ok(v)
    } else {
        Err(format!(
            "{v} is outside (0, 1] (1 disables early termination)"
        ))
    }
}

fn parse_floats(text: &str) -> Result<Vec<f32>, String> {
    text.split(',')
        .map(|part| match part.trim().parse::<f32>() {
            Ok(v) if v.is_finite() => Ok(v),
            Ok(v) => Err(format!("{v} is not finite in {text:?}")),
            Err(_) => Err(format!("{:?} is not a number in {text:?}", part.trim())),
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn values_parse_or_name_the_problem() {
        assert_eq!(parse_size("64x32"), Ok((64, 32)));
        assert!(parse_size("0x5").unwrap_err().contains("1..=16384"));
        assert!(parse_size("64").unwrap_err().contains("WxH"));
        assert_eq!(parse_rgb("0.5"), Ok(Vec3::splat(0.5)));
        assert_eq!(parse_rgb("1,0,0.5"), Ok(Vec3::new(1.0, 0.0, 0.5)));
        assert!(parse_rgb("1,2").is_err());
        assert!(parse_rgb("-1").unwrap_err().contains("negative"));
        assert_eq!(parse_vec3("-1,2,3"), Ok(Vec3::new(-1.0, 2.0, 3.0)));
        assert_eq!(
            parse_dvec3("7000000.25,-1,3"),
            Ok(DVec3::new(7000000.25, -1.0, 3.0))
        );
        assert!(parse_dvec3("1,inf,3").unwrap_err().contains("not finite"));
        assert!(parse_dvec3("1,2").unwrap_err().contains("three numbers"));
        assert!(parse_vec3("1,nan,3").unwrap_err().contains("not finite"));
        assert!(parse_vec3("1,x,3").unwrap_err().contains("not a number"));
        assert!(parse_positive("0").is_err());
        assert!(parse_early_termination("1.5").is_err());
        assert_eq!(parse_method("PPI"), Ok(Method::Ppi));
        assert_eq!(parse_sort("MPVO"), Ok(SortKind::Mpvo));
        assert!(
            parse_sort("bsp")
                .unwrap_err()
                .contains("centroid, mpvo, mpvonc")
        );
        assert!(
            parse_method("simpson")
                .unwrap_err()
                .contains("expected one of")
        );
    }
}
