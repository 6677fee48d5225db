//! Whitted ray tracing, as the lecture writes it: the textbook core of raytree.
//!
//! ```text
//! I = ka·Ia·O + Σ_ℓ s·fatt·Iℓ·(kd·O·(n·l) + ks·(h·n)^m)  +  kr·I_r  +  kt·I_t
//!     └─ ambient ┘  └──── each light, times its shadow factor s ───┘   └ reflection ┘ └ refraction ┘
//! ```
//!
//! `shade` computes a ray's intensity in the order the equation reads: the local terms with a
//! shadow ray per light, then the reflection ray, then the refraction ray (or, past the
//! limiting angle, total internal reflection). A secondary ray is one level deeper; it is not
//! traced at the maximum depth, nor when its weight (the product of the coefficients on its
//! way from the eye) falls below the adaptive threshold. Intensities are collected from the
//! leaves up as the recursion returns.
//!
//! The same code renders images and builds the ray trees the explorer shows: a `Recorder`
//! watches it (`NoRecorder` compiles to nothing). It asks a `Search` for hits: the scene's own,
//! or the renderer's faster one, which finds the same hits.

use glam::DVec3;

use super::media::Across;
use super::task::Task;
use super::tree::{Indices, LightTerm, LobeKind, Local, Termination};
use super::Tracer;
use crate::geometry::Ray;
use crate::scene::{Hit, Interaction};
use crate::shading::local::{ambient, light_terms, transmitted_terms, LightTerms};
use crate::shading::optics::{fresnel_weights, reflect, refract};
use crate::shading::{lobe, Light, LightSample, Lobe, Material, Paint};
use crate::trace::recorder::Recorder;

impl<R: Recorder> Tracer<'_, R> {
    /// Traces one ray: its intensity, and how far away it comes from (∞ for the background).
    pub(crate) fn trace(&mut self, task: &Task) -> (DVec3, f64) {
        let hit = self
            .search
            .nearest(&task.ray, 0.0, f64::INFINITY, &mut self.stats);
        let t_hit = hit.map_or(f64::INFINITY, |h| h.t);
        if self.options.stop_at_lights {
            if let Some((k, t)) = self.light_ahead(&task.ray, t_hit) {
                return (self.lamp(task, k), t);
            }
        }
        (self.shade(task, hit), t_hit)
    }

    // --- The stop rules of seeds 000 and 002 ---

    /// The nearest light source the ray reaches before `t_max` (an area or sphere light: a
    /// point or directional light has no surface to hit).
    fn light_ahead(&self, ray: &Ray, t_max: f64) -> Option<(usize, f64)> {
        let mut nearest = None;
        for (k, light) in self.scene.lights.iter().enumerate() {
            let limit = nearest.map_or(t_max, |(_, t)| t);
            if let Some(h) = light.emitter_hit(ray, limit) {
                nearest = Some((k, h.t));
            }
        }
        nearest
    }

    /// A ray that hits light k stops there: it brings back the light's intensity.
    fn lamp(&mut self, task: &Task, k: usize) -> DVec3 {
        self.count(task.kind);
        task.begin(&mut self.rec);
        let light = &self.scene.lights[k];
        self.rec.lamp(&light.name);
        self.rec.end(light.intensity, Some(Termination::Light));
        light.intensity
    }

    /// Whether a surface ends the path under seed 002's rule: a diffuse surface (kd > 0 where
    /// the ray meets it) sends no reflection or refraction ray.
    pub(crate) fn stops_at(&self, at: &Paint) -> bool {
        self.options.stop_at_diffuse && at.kd > 0.0
    }

    /// The intensity of a ray from its nearest hit: I = I_local + kr·I_r + kt·I_t.
    pub(crate) fn shade(&mut self, task: &Task, hit: Option<Hit>) -> DVec3 {
        self.count(task.kind);
        task.begin(&mut self.rec);
        let Some(hit) = hit else {
            let background = self.scene.background;
            self.rec.end(background, Some(Termination::Background));
            return background;
        };
        let si = self.scene.interaction(&task.ray, &hit);
        if R::ACTIVE {
            self.rec.hit(self.hit_info(&task.ray, hit.t, &si));
        }
        let color = self.local(task, &si);
        self.finish(task, &si, color)
    }

    /// The node's total from its local intensity: the secondary rays' kr·I_r + kt·I_t added.
    pub(crate) fn finish(&mut self, task: &Task, si: &Interaction, mut color: DVec3) -> DVec3 {
        let mut stopped = None;
        if si.paint.sends_rays() {
            if self.stops_at(&si.paint) {
                stopped = Some(Termination::Diffuse);
            } else {
                color += self.secondary(task, si);
            }
        }
        self.rec.end(color, stopped);
        color
    }

    // --- Local illumination, with a shadow ray per light ---

    /// I_local = ka·Ia·O + Σ_ℓ s·(diffuse + specular).
    fn local(&mut self, task: &Task, si: &Interaction) -> DVec3 {
        let scene = self.scene;
        let m = scene.material(si.material);
        let mut color = ambient(m, &si.paint, scene.ambient);
        let mut terms = Vec::new();
        for (k, light) in scene.lights.iter().enumerate() {
            let (sample, lit, skipped) = self.light_share(m, si, task, k, R::ACTIVE);
            let s = match skipped {
                Some(_) => 0.0,
                None => self.shadow_factor(si, task.depth, &sample, light),
            };
            color += s * (lit.diffuse + lit.specular);
            if R::ACTIVE {
                terms.push(LightTerm {
                    light: light.name.clone(),
                    shadow: s,
                    l: sample.l,
                    n_dot_l: lit.n_dot_l,
                    attenuation: sample.attenuation,
                    highlight_cos: lit.highlight_cos,
                    diffuse: s * lit.diffuse,
                    specular: s * lit.specular,
                    skipped: skipped.map(str::to_string),
                });
            }
        }
        if R::ACTIVE {
            self.rec.local(Local {
                ambient: ambient(m, &si.paint, scene.ambient),
                lights: terms,
                ..self.surface(si)
            });
        }
        color
    }

    /// Light k's diffuse and specular terms at a point, before the shadow factor, and why no
    /// shadow ray is needed, if none is (then s = 0). `shows`: the terms go into a tree.
    ///
    /// A light behind the surface gives nothing, unless the material takes Hall's transmitted
    /// highlight: then a transparent surface is lit through itself, its highlight made with H′
    /// (`transmitted_terms`, η from the media on both sides), and the shadow ray goes through
    /// the surface toward the light.
    pub(crate) fn light_share(
        &mut self,
        m: &Material,
        si: &Interaction,
        task: &Task,
        k: usize,
        shows: bool,
    ) -> (LightSample, LightTerms, Option<&'static str>) {
        let scene = self.scene;
        let light = &scene.lights[k];
        let sample = light.sample(si.point);
        let strength = sample.attenuation * light.intensity;
        let v = -task.ray.dir;
        let through = m.transmitted_highlight && si.paint.kt > 0.0 && si.normal.dot(sample.l) < 0.0;
        let lit = if through {
            let across = self.across(task, si, m);
            let eta = across.n2 / across.n1;
            transmitted_terms(m, &si.paint, si.normal, v, sample.l, eta, strength)
        } else {
            light_terms(m, &si.paint, si.normal, v, sample.l, strength, shows)
        };
        let skipped = self.no_shadow_ray(si, k, &sample, lit.n_dot_l, through);
        (sample, lit, skipped)
    }

    /// Why light k needs no shadow ray at a surface, if it does not (then s = 0): it is behind
    /// the surface, dark, sends nothing toward the point (`toward`, its sample there, has
    /// fatt = 0), or is outside the convex solid the point is inside of. `through`: the light
    /// is seen through the surface (Hall's transmitted highlight).
    pub(crate) fn no_shadow_ray(
        &mut self,
        si: &Interaction,
        k: usize,
        toward: &LightSample,
        n_dot_l: f64,
        through: bool,
    ) -> Option<&'static str> {
        if n_dot_l <= 0.0 && !through {
            self.stats.shadow_skipped_backfacing += 1;
            Some("light behind the surface (n·l ≤ 0)")
        } else if self.scene.lights[k].is_dark() {
            self.stats.shadow_skipped_dark += 1;
            Some("light has zero intensity")
        } else if toward.attenuation == 0.0 {
            self.stats.shadow_skipped_dark += 1;
            Some("the light sends nothing this way: a rectangle lights only the side of u × v")
        } else if si.inside
            && !through
            && self.options.shadows
            && self.scene.features.hides_light_inside(si.object, k)
        {
            // The way to a light outside a convex solid leaves the solid, whose surface is in
            // the way (unless it leaves through the very surface it starts on).
            self.stats.shadow_skipped_inside += 1;
            Some("inside a convex solid the light is outside of: the solid blocks it")
        } else {
            None
        }
    }

    /// s for one light: a shadow ray from the surface toward it. A point light is blocked by a
    /// hit with 0 < t < distance, a directional one by any hit with t > 0. An area light gets
    /// one shadow ray per point of its grid; s is the fraction that get through.
    pub(crate) fn shadow_factor(
        &mut self,
        si: &Interaction,
        depth: u32,
        toward: &LightSample,
        light: &Light,
    ) -> f64 {
        let count = light.shadow_rays();
        let mut visible = 0u32;
        let mut first_blocker = None;
        for k in 0..count {
            let (dir, dist) = match light.shadow_point(k, si.point) {
                Some(q) => {
                    let to = q - si.point;
                    (to.normalize(), to.length())
                }
                None => (toward.l, toward.distance),
            };
            self.stats.shadow_rays += 1;
            let (ray, t_max) = self.shadow_ray(si, dir, dist);
            let blocker = if self.options.shadows {
                self.search.blocker(&ray, 0.0, t_max, &mut self.stats)
            } else {
                None
            };
            match blocker {
                None => visible += 1,
                Some(h) if R::ACTIVE && first_blocker.is_none() => first_blocker = Some((ray, h)),
                Some(_) => {}
            }
        }
        let s = visible as f64 / count as f64;
        if R::ACTIVE {
            self.record_shadow(si, depth, toward, light, s, first_blocker);
        }
        s
    }

    /// A shadow ray from the surface along `dir`, and how far it looks for blockers: up to a
    /// light `distance` away.
    pub(crate) fn shadow_ray(&self, si: &Interaction, dir: DVec3, distance: f64) -> (Ray, f64) {
        let (from, moved) = self.scene.offset(si, dir);
        (Ray { origin: from, dir }, shadow_reach(distance, moved))
    }

    // --- Reflection and refraction ---

    /// kr·I_r + kt·I_t at a surface: the mirror ray r = d − 2(d·n)n, and the transmitted ray
    /// by Snell's law, or past the limiting angle, total internal reflection. kr and kt are
    /// the material's, after the Fresnel term.
    pub(crate) fn secondary(&mut self, task: &Task, si: &Interaction) -> DVec3 {
        let m = self.scene.material(si.material);
        let d = task.ray.dir;
        let (across, kr, kt) = self.coefficients(task, si, m);
        let indices = across.indices();
        let mirror = reflect(d, si.normal);
        let refracted = if kt > 0.0 {
            refract(d, si.normal, indices.n1, indices.n2)
        } else {
            None
        };
        // Past the limiting angle the transmitted light turns back along the mirror ray. A
        // surface that reflects too already sends that very ray (unless a lobe spreads either):
        // it is traced once, for both shares.
        let shared = kt > 0.0
            && refracted.is_none()
            && kr > 0.0
            && m.glossy.is_none()
            && m.frosted.is_none();
        let mut sum = DVec3::ZERO;
        let mut reflected = None;
        if kr > 0.0 {
            let ray = self.spawn(si, mirror);
            let reflection = if shared {
                task.reflection_and_transmission(ray, kr, kt)
            } else {
                task.reflection(ray, kr)
            };
            let color = match m.glossy {
                None => self.child(&reflection),
                Some(lobe) => self.cone(&reflection, si, (lobe, LobeKind::Glossy)),
            };
            if shared && self.limit(&reflection).is_none() {
                reflected = Some(color);
            }
            sum += kr * color;
        }
        if kt > 0.0 {
            sum += kt
                * match refracted {
                    Some(dir) => {
                        let ray = self.spawn_through(si, dir);
                        let refraction = task.refraction(ray, kt, across.beyond, indices);
                        match m.frosted {
                            None => self.child(&refraction),
                            Some(lobe) => self.cone(&refraction, si, (lobe, LobeKind::Frosted)),
                        }
                    }
                    None if shared => self.along_reflection(task, si, kt, indices, reflected),
                    None => self.total_internal_reflection(task, si, mirror, kt, indices),
                };
        }
        sum
    }

    /// The media on both sides of the surface, and kr and kt there after the Fresnel term.
    pub(crate) fn coefficients(
        &mut self,
        task: &Task,
        si: &Interaction,
        m: &Material,
    ) -> (Across, f64, f64) {
        let across = self.across(task, si, m);
        let (kr, kt) = fresnel_weights(
            m.fresnel,
            -task.ray.dir.dot(si.normal),
            (across.n1, across.n2),
            (si.paint.kr, si.paint.kt),
        );
        (across, kr, kt)
    }

    /// Beyond the limiting angle no light is transmitted: the refraction ray becomes a
    /// reflection ray that stays inside. The tree shows a refraction node that ends in
    /// "total_internal_reflection" with that mirror ray as its child. A frosted surface
    /// spreads it too, drawn from the frosted lobe about the mirror direction: the rough face
    /// that blurs the light it lets through blurs the light it turns back (a perfect mirror
    /// there would keep a ray in a sphere at one angle, bouncing until the depth limit). (A
    /// surface that reflects as well sends that mirror ray already: `along_reflection`.)
    fn total_internal_reflection(
        &mut self,
        task: &Task,
        si: &Interaction,
        mirror: DVec3,
        kt: f64,
        indices: Indices,
    ) -> DVec3 {
        let refraction = turned_back(task, si, kt, indices);
        if self.limit(&refraction).is_some() {
            // The refraction ray would not be traced anyway: record it as cut off.
            return self.child(&refraction);
        }
        self.stats.total_internal_reflections += 1;
        refraction.begin(&mut self.rec);
        let inside = task.mirror_inside(self.spawn(si, mirror), kt);
        let color = match self.scene.material(si.material).frosted {
            None => self.child(&inside),
            Some(lobe) => self.cone(&inside, si, (lobe, LobeKind::Frosted)),
        };
        self.rec
            .end(color, Some(Termination::TotalInternalReflection));
        color
    }

    /// Total internal reflection at a surface that also reflects: the refraction node ends
    /// there, and its share follows the reflection ray (`reflected`, its intensity, None where
    /// that ray was cut off, and then so is this one).
    fn along_reflection(
        &mut self,
        task: &Task,
        si: &Interaction,
        kt: f64,
        indices: Indices,
        reflected: Option<DVec3>,
    ) -> DVec3 {
        let refraction = turned_back(task, si, kt, indices);
        let Some(color) = reflected else {
            return self.child(&refraction);
        };
        self.stats.total_internal_reflections += 1;
        refraction.begin(&mut self.rec);
        self.rec
            .end(color, Some(Termination::TotalInternalReflection));
        color
    }

    // --- Depth control: the maximum depth and the adaptive threshold ---

    /// Traces a secondary ray unless the depth limit or the adaptive threshold stops it; its
    /// intensity as its parent receives it.
    fn child(&mut self, task: &Task) -> DVec3 {
        if let Some(why) = self.stopped(task) {
            if R::ACTIVE {
                task.begin(&mut self.rec);
                self.rec.end(DVec3::ZERO, Some(why));
            }
            return DVec3::ZERO;
        }
        let (color, distance) = self.trace(task);
        if R::ACTIVE {
            if let Some(divisor) = self.attenuation_at(distance) {
                self.rec.attenuated(divisor);
            }
        }
        self.attenuated(color, distance)
    }

    /// Why a secondary ray is not traced, if it is not: its depth reached the limit, or its
    /// weight fell below the adaptive threshold (it could change the pixel too little).
    #[inline]
    pub(crate) fn limit(&self, task: &Task) -> Option<Termination> {
        if task.depth >= self.options.max_depth {
            Some(Termination::MaxDepth)
        } else if task.weight < self.scene.adaptive_threshold {
            Some(Termination::Adaptive)
        } else {
            None
        }
    }

    /// `limit`, counted among the work skipped.
    #[inline]
    pub(crate) fn stopped(&mut self, task: &Task) -> Option<Termination> {
        let why = self.limit(task);
        match why {
            Some(Termination::MaxDepth) => self.stats.max_depth_cutoffs += 1,
            Some(Termination::Adaptive) => self.stats.adaptive_cutoffs += 1,
            _ => {}
        }
        why
    }

    /// A secondary ray's intensity as its parent receives it: with `secondary_attenuation`,
    /// divided by c0 + c1·d + c2·d² for the distance d it travelled (seed 004).
    pub(crate) fn attenuated(&self, color: DVec3, distance: f64) -> DVec3 {
        match self.attenuation_at(distance) {
            Some(divisor) => color / divisor,
            None => color,
        }
    }

    /// c0 + c1·d + c2·d² for a secondary ray that travelled d, with `secondary_attenuation`.
    fn attenuation_at(&self, distance: f64) -> Option<f64> {
        match self.scene.secondary_attenuation {
            Some([c0, c1, c2]) if distance.is_finite() => {
                Some(c0 + c1 * distance + c2 * distance * distance)
            }
            _ => None,
        }
    }

    // --- Monte Carlo: glossy reflection and frosted refraction ---

    /// Seed 000's Monte Carlo reflection and refraction: the light arriving in a cone about
    /// the principal direction is the average of n rays drawn from the lobe, each traced
    /// recursively. The tree shows the cone as a node whose children are the sampled rays.
    fn cone(
        &mut self,
        principal: &Task,
        si: &Interaction,
        (lobe, kind): (Lobe, LobeKind),
    ) -> DVec3 {
        let n = if principal.split { 1 } else { lobe.samples };
        if R::ACTIVE {
            principal.begin(&mut self.rec);
            self.rec.samples(n, kind);
        }
        let mut sum = DVec3::ZERO;
        for _ in 0..n {
            let (u1, u2) = (self.rng.uniform(), self.rng.uniform());
            let dir = lobe::spread(lobe.shape, principal.ray.dir, si.normal, u1, u2);
            let sample = Task {
                ray: self.spawn(si, dir),
                coefficient: 1.0 / n as f64,
                split: true,
                ..*principal
            };
            // Counted among the rays traced only if it is traced (`child` may cut it off).
            self.stats.glossy_rays += self.limit(&sample).is_none() as u64;
            sum += self.child(&sample);
        }
        let mean = sum / n as f64;
        if R::ACTIVE {
            self.rec.end(mean, None);
        }
        mean
    }

    /// The one place secondary rays leave a surface: the origin moves off the surface, along
    /// the normal, to the side the new ray travels into, so it cannot hit its own surface.
    pub(crate) fn spawn(&self, si: &Interaction, dir: DVec3) -> Ray {
        Ray {
            origin: self.scene.offset(si, dir).0,
            dir,
        }
    }

    /// A refracted ray leaves from the far side of the surface, the side it goes through to:
    /// also at the limiting angle, where it runs along the surface (Snell's k = 0) and its
    /// direction alone would not say which side.
    pub(crate) fn spawn_through(&self, si: &Interaction, dir: DVec3) -> Ray {
        Ray {
            origin: self.scene.offset_to(si, false).0,
            dir,
        }
    }
}

/// The refraction node of a ray past the limiting angle: it would go on straight from the
/// hit, in the media it is in, and is never traced.
fn turned_back(task: &Task, si: &Interaction, kt: f64, indices: Indices) -> Task {
    let straight_on = Ray {
        origin: si.point,
        dir: task.ray.dir,
    };
    task.refraction(straight_on, kt, task.media, indices)
}

/// How far a shadow ray that starts `moved` off the surface looks for blockers: up to the light
/// (the normal is a unit vector, so the offset moved the origin by exactly `moved`).
pub fn shadow_reach(distance: f64, moved: f64) -> f64 {
    if distance.is_finite() {
        (distance - moved).max(0.0)
    } else {
        distance
    }
}
