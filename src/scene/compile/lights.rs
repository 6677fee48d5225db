//! The lights: point, directional, rectangle and sphere lights, with their attenuation and
//! (for area lights) the material of their surface.

use std::collections::{BTreeMap, HashSet};

use glam::DVec3;
use serde_saphyr::Spanned;

use super::{invalid, nonzero, number, pos, printable_name, Invalid, Pos};
use crate::scene::format::{LightSpec, Num, SceneFile};
use crate::shading::{Light, LightKind};

/// The file's lights, in order, with names unique and surfaces resolved.
pub fn of(file: &SceneFile, materials: &BTreeMap<String, u32>) -> Result<Vec<Light>, Invalid> {
    let mut lights = Vec::new();
    let mut light_names = HashSet::new();
    for (i, l) in file.lights.iter().enumerate() {
        let light = light(&l.value, pos(l), i)?;
        printable_name(&light.name, pos(l), "light")?;
        if !light_names.insert(light.name.clone()) {
            return invalid(pos(l), format!("duplicate light name `{}`", light.name));
        }
        lights.push(light);
    }
    for (l, light) in file.lights.iter().zip(&mut lights) {
        let Some(surface) = &l.value.surface else {
            continue;
        };
        if !matches!(
            light.kind,
            LightKind::Rect { .. } | LightKind::Sphere { .. }
        ) {
            return invalid(
                pos(surface),
                format!(
                    "light `{}`: only area (`rect` and `sphere`) lights have a surface",
                    light.name
                ),
            );
        }
        match materials.get(&surface.value) {
            Some(&m) => light.surface = Some(m),
            None => {
                return invalid(
                    pos(surface),
                    format!(
                        "light `{}`: unknown material `{}` for its surface",
                        light.name, surface.value
                    ),
                )
            }
        }
    }
    Ok(lights)
}

pub fn attenuation(a: &Spanned<[Num; 3]>) -> Result<[f64; 3], Invalid> {
    let [c0, c1, c2] = a.value.map(|n| n.0);
    if c0 < 0.0 || c1 < 0.0 || c2 < 0.0 || c0 + c1 + c2 <= 0.0 {
        return invalid(
            pos(a),
            "attenuation [c0, c1, c2] must be ≥ 0 and not all zero",
        );
    }
    Ok([c0, c1, c2])
}

fn light(l: &LightSpec, p: Pos, i: usize) -> Result<Light, Invalid> {
    let name = l.name.clone().unwrap_or_else(|| format!("light{}", i + 1));
    let intensity = l.intensity.map_or(DVec3::ONE, |t| t.0);
    if intensity.min_element() < 0.0 {
        return invalid(p, format!("light `{name}` has a negative intensity"));
    }
    let given = [
        l.point.is_some(),
        l.direction.is_some(),
        l.rect.is_some(),
        l.sphere.is_some(),
    ]
    .iter()
    .filter(|&&b| b)
    .count();
    if given != 1 {
        return invalid(
            p,
            format!("light `{name}` needs exactly one of `point`, `direction`, `rect` or `sphere`"),
        );
    }
    if l.samples.is_some() && l.rect.is_none() && l.sphere.is_none() {
        return invalid(
            p,
            format!("light `{name}`: `samples` is for area (`rect` and `sphere`) lights"),
        );
    }
    let samples = match &l.samples {
        None => 3,
        Some(s) if !(1..=64).contains(&s.value) => {
            return invalid(
                pos(s),
                format!(
                    "light `{name}`: samples must be between 1 and 64, got {}",
                    s.value
                ),
            )
        }
        Some(s) => s.value as u32,
    };
    let kind = if let Some(position) = l.point.map(|v| v.0) {
        let attenuation = match &l.attenuation {
            Some(a) => attenuation(a)?,
            None => [1.0, 0.0, 0.0],
        };
        LightKind::Point {
            position,
            attenuation,
        }
    } else if let Some(sphere) = &l.sphere {
        let radius = sphere.value.radius.value.0;
        if radius <= 0.0 {
            return invalid(
                pos(&sphere.value.radius),
                format!(
                    "light `{name}`: the sphere's radius must be > 0, got {}",
                    number(radius)
                ),
            );
        }
        LightKind::Sphere {
            center: sphere.value.center.0,
            radius,
            attenuation: match &l.attenuation {
                Some(a) => attenuation(a)?,
                None => [1.0, 0.0, 0.0],
            },
            samples,
        }
    } else if l.attenuation.is_some() {
        return invalid(
            p,
            format!("light `{name}`: only point and sphere lights have distance attenuation"),
        );
    } else if let Some(d) = &l.direction {
        LightKind::Directional {
            direction: nonzero(d.value.0, pos(d), "light direction")?,
        }
    } else {
        let r = l.rect.as_ref().expect("counted above");
        let (corner, u, v) = (r.value.corner.0, r.value.u.0, r.value.v.0);
        if u.cross(v).length() < 1e-12 {
            return invalid(
                pos(r),
                format!(
                    "light `{name}`: the rectangle's edges u and v must not be parallel or zero"
                ),
            );
        }
        LightKind::Rect {
            corner,
            u,
            v,
            samples,
        }
    };
    Ok(Light {
        name,
        kind,
        intensity,
        surface: None,
    })
}
