//! Mass, centre of mass and inertia tensor of a closed triangle mesh: exactly by Mirtich's
//! surface-integral algorithm (B. Mirtich, "Fast and Accurate Computation of Polyhedral Mass
//! Properties", JGT 1996), or approximately from a lattice of point masses (the lecture's
//! "approximation with points").
//!
//! Sign convention: the inertia tensor is `I = ∫ (|r|² 𝟙 − r rᵀ) dm` about the centre of mass,
//! so the off-diagonal entries are *minus* the products of inertia: `I_xy = −∫ x y dm`.

use super::mesh::TriMesh;
use glam::{DMat3, DVec3};

/// Mass properties of a solid; the inertia tensor is about `center`, in the mesh's axes.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct MassProperties {
    /// kg (volume × density)
    pub mass: f64,
    /// metres, in the mesh's coordinates
    pub center: DVec3,
    /// kg m², about `center`
    pub inertia: DMat3,
}

impl MassProperties {
    /// The same solid with a different uniform density (kg/m³); `self` must be at density 1.
    pub fn with_density(self, density: f64) -> Self {
        Self {
            mass: self.mass * density,
            center: self.center,
            inertia: self.inertia * density,
        }
    }

    /// Volume, if `self` is at density 1.
    pub fn volume(&self) -> f64 {
        self.mass
    }
}

/// Exact mass properties of a closed, outward-oriented triangle mesh at density 1.
///
/// The integrals are taken about the centre of the bounding box, not the world origin: they
/// contain fourth powers of coordinates, so a mesh far from the origin would lose digits to
/// cancellation (and the result would depend on where the mesh sits).
pub fn mirtich(mesh: &TriMesh) -> MassProperties {
    let (lo, hi) = mesh.bounds();
    let origin = 0.5 * (lo + hi);
    // volume integrals: T0 = ∫1, T1 = ∫(x, y, z), T2 = ∫(x², y², z²), TP = ∫(xy, yz, zx)
    let mut t0 = 0.0;
    let mut t1 = [0.0f64; 3];
    let mut t2 = [0.0f64; 3];
    let mut tp = [0.0f64; 3];
    for i in 0..mesh.triangles.len() {
        let p = mesh.triangle(i).map(|v| v - origin);
        let n_raw = (p[1] - p[0]).cross(p[2] - p[0]);
        let len = n_raw.length();
        if len == 0.0 || !len.is_finite() {
            continue; // a degenerate triangle contributes nothing
        }
        let n = n_raw / len;
        let w = -n.dot(p[0]);
        let na = n.abs();
        // C: the axis the face is projected along (largest normal component); A, B follow it
        let c = if na.x > na.y && na.x > na.z {
            0
        } else if na.y > na.z {
            1
        } else {
            2
        };
        let a = (c + 1) % 3;
        let b = (a + 1) % 3;
        let f = face_integrals(&p, n.to_array(), w, a, b, c);
        let nv = n.to_array();
        t0 += nv[0]
            * if a == 0 {
                f.fa
            } else if b == 0 {
                f.fb
            } else {
                f.fc
            };
        t1[a] += nv[a] * f.faa;
        t1[b] += nv[b] * f.fbb;
        t1[c] += nv[c] * f.fcc;
        t2[a] += nv[a] * f.faaa;
        t2[b] += nv[b] * f.fbbb;
        t2[c] += nv[c] * f.fccc;
        tp[a] += nv[a] * f.faab;
        tp[b] += nv[b] * f.fbbc;
        tp[c] += nv[c] * f.fcca;
    }
    for k in 0..3 {
        t1[k] /= 2.0;
        t2[k] /= 3.0;
        tp[k] /= 2.0;
    }
    let mass = t0;
    if mass.abs() < 1e-300 {
        return MassProperties {
            mass: 0.0,
            center: DVec3::ZERO,
            inertia: DMat3::ZERO,
        };
    }
    let r = DVec3::from_array(t1) / mass;
    // about the origin, then moved to the centre of mass (parallel-axis theorem)
    let (xx, yy, zz) = (
        t2[1] + t2[2] - mass * (r.y * r.y + r.z * r.z),
        t2[2] + t2[0] - mass * (r.z * r.z + r.x * r.x),
        t2[0] + t2[1] - mass * (r.x * r.x + r.y * r.y),
    );
    let xy = -tp[0] + mass * r.x * r.y;
    let yz = -tp[1] + mass * r.y * r.z;
    let zx = -tp[2] + mass * r.z * r.x;
    let inertia = DMat3::from_cols(
        DVec3::new(xx, xy, zx),
        DVec3::new(xy, yy, yz),
        DVec3::new(zx, yz, zz),
    );
    MassProperties {
        mass,
        center: r + origin,
        inertia,
    }
}

struct FaceIntegrals {
    fa: f64,
    fb: f64,
    fc: f64,
    faa: f64,
    fbb: f64,
    fcc: f64,
    faaa: f64,
    fbbb: f64,
    fccc: f64,
    faab: f64,
    fbbc: f64,
    fcca: f64,
}

/// Mirtich's face integrals over one triangle from its projection onto the AB plane.
fn face_integrals(
    p: &[DVec3; 3],
    n: [f64; 3],
    w: f64,
    a: usize,
    b: usize,
    c: usize,
) -> FaceIntegrals {
    let (mut p1, mut pa, mut pb, mut paa, mut pab, mut pbb) = (0.0, 0.0, 0.0, 0.0, 0.0, 0.0);
    let (mut paaa, mut paab, mut pabb, mut pbbb) = (0.0, 0.0, 0.0, 0.0);
    for i in 0..3 {
        let q0 = p[i].to_array();
        let q1 = p[(i + 1) % 3].to_array();
        let (a0, b0, a1, b1) = (q0[a], q0[b], q1[a], q1[b]);
        let (da, db) = (a1 - a0, b1 - b0);
        let (a0_2, b0_2, a1_2, b1_2) = (a0 * a0, b0 * b0, a1 * a1, b1 * b1);
        let (a0_3, b0_3, a1_3, b1_3) = (a0_2 * a0, b0_2 * b0, a1_2 * a1, b1_2 * b1);
        let (a0_4, b0_4) = (a0_3 * a0, b0_3 * b0);
        let c1 = a1 + a0;
        let ca = a1 * c1 + a0_2;
        let caa = a1 * ca + a0_3;
        let caaa = a1 * caa + a0_4;
        let cb = b1 * (b1 + b0) + b0_2;
        let cbb = b1 * cb + b0_3;
        let cbbb = b1 * cbb + b0_4;
        let cab = 3.0 * a1_2 + 2.0 * a1 * a0 + a0_2;
        let kab = a1_2 + 2.0 * a1 * a0 + 3.0 * a0_2;
        let caab = a0 * cab + 4.0 * a1_3;
        let kaab = a1 * kab + 4.0 * a0_3;
        let cabb = 4.0 * b1_3 + 3.0 * b1_2 * b0 + 2.0 * b1 * b0_2 + b0_3;
        let kabb = b1_3 + 2.0 * b1_2 * b0 + 3.0 * b1 * b0_2 + 4.0 * b0_3;
        p1 += db * c1;
        pa += db * ca;
        paa += db * caa;
        paaa += db * caaa;
        pb += da * cb;
        pbb += da * cbb;
        pbbb += da * cbbb;
        pab += db * (b1 * cab + b0 * kab);
        paab += db * (b1 * caab + b0 * kaab);
        pabb += da * (a1 * cabb + a0 * kabb);
    }
    p1 /= 2.0;
    pa /= 6.0;
    paa /= 12.0;
    paaa /= 20.0;
    pb /= -6.0;
    pbb /= -12.0;
    pbbb /= -20.0;
    pab /= 24.0;
    paab /= 60.0;
    pabb /= -60.0;

    let (na, nb, nc) = (n[a], n[b], n[c]);
    let k1 = 1.0 / nc;
    let k2 = k1 * k1;
    let k3 = k2 * k1;
    let k4 = k3 * k1;
    FaceIntegrals {
        fa: k1 * pa,
        fb: k1 * pb,
        fc: -k2 * (na * pa + nb * pb + w * p1),
        faa: k1 * paa,
        fbb: k1 * pbb,
        fcc: k3
            * (na * na * paa
                + 2.0 * na * nb * pab
                + nb * nb * pbb
                + w * (2.0 * (na * pa + nb * pb) + w * p1)),
        faaa: k1 * paaa,
        fbbb: k1 * pbbb,
        fccc: -k4
            * (na * na * na * paaa
                + 3.0 * na * na * nb * paab
                + 3.0 * na * nb * nb * pabb
                + nb * nb * nb * pbbb
                + 3.0 * w * (na * na * paa + 2.0 * na * nb * pab + nb * nb * pbb)
                + w * w * (3.0 * (na * pa + nb * pb) + w * p1)),
        faab: k1 * paab,
        fbbc: -k2 * (na * pabb + nb * pbbb + w * pbb),
        fcca: k3
            * (na * na * paaa
                + 2.0 * na * nb * paab
                + nb * nb * pabb
                + w * (2.0 * (na * paa + nb * pab) + w * pa)),
    }
}

/// Centres of the cells of an `n × n × n` lattice over the mesh's bounding box that lie inside
/// the mesh, and the volume of one cell. Inside-ness: the signed number of surface crossings
/// of a ray along +x (non-zero winding), one ray per lattice row.
pub fn lattice_points(mesh: &TriMesh, n: usize) -> (Vec<DVec3>, f64) {
    let n = n.max(1);
    let (lo, hi) = mesh.bounds();
    let cell = (hi - lo) / n as f64;
    let cell_volume = cell.x * cell.y * cell.z;
    let mut points = Vec::new();
    let mut crossings: Vec<(f64, i32)> = Vec::new();
    // a tiny skew keeps rows off shared edges and vertices of the mesh; it moves no point
    let skew = (hi - lo).max_element().max(1e-12) * 1e-9;
    for k in 0..n {
        let z = lo.z + (k as f64 + 0.5) * cell.z;
        for j in 0..n {
            let y = lo.y + (j as f64 + 0.5) * cell.y;
            let (ry, rz) = (y + skew * std::f64::consts::SQRT_2, z + skew * 1.7320508);
            crossings.clear();
            for t in 0..mesh.triangles.len() {
                if let Some(hit) = ray_x_crossing(&mesh.triangle(t), ry, rz) {
                    crossings.push(hit);
                }
            }
            crossings.sort_by(|a, b| a.0.total_cmp(&b.0));
            for i in 0..n {
                let x = lo.x + (i as f64 + 0.5) * cell.x;
                // winding = signed crossings to the right of x
                let winding: i32 = crossings.iter().filter(|c| c.0 > x).map(|c| c.1).sum();
                if winding != 0 {
                    points.push(DVec3::new(x, y, z));
                }
            }
        }
    }
    (points, cell_volume)
}

/// Where the line {(s, y, z)} crosses the triangle, and the sign of the normal's x (±1).
fn ray_x_crossing(p: &[DVec3; 3], y: f64, z: f64) -> Option<(f64, i32)> {
    // 2-D edge functions in the yz plane
    let e = |a: DVec3, b: DVec3| (b.y - a.y) * (z - a.z) - (b.z - a.z) * (y - a.y);
    let (w0, w1, w2) = (e(p[1], p[2]), e(p[2], p[0]), e(p[0], p[1]));
    let sum = w0 + w1 + w2;
    if sum == 0.0 {
        return None; // triangle parallel to the ray
    }
    let inside = (w0 >= 0.0 && w1 >= 0.0 && w2 >= 0.0) || (w0 <= 0.0 && w1 <= 0.0 && w2 <= 0.0);
    if !inside {
        return None;
    }
    let x = (w0 * p[0].x + w1 * p[1].x + w2 * p[2].x) / sum;
    let nx = (p[1] - p[0]).cross(p[2] - p[0]).x;
    Some((x, if nx > 0.0 { 1 } else { -1 }))
}

/// Approximate mass properties at density 1 from the `n³` lattice's inside cell centres, each
/// a point of mass = cell volume.
pub fn point_lattice(mesh: &TriMesh, n: usize) -> MassProperties {
    let (points, cell_volume) = lattice_points(mesh, n);
    point_masses(&points, cell_volume)
}

/// Mass properties of equal point masses `m` at `points`.
pub fn point_masses(points: &[DVec3], m: f64) -> MassProperties {
    if points.is_empty() {
        return MassProperties {
            mass: 0.0,
            center: DVec3::ZERO,
            inertia: DMat3::ZERO,
        };
    }
    let mass = m * points.len() as f64;
    let center = points.iter().copied().sum::<DVec3>() / points.len() as f64;
    let mut inertia = DMat3::ZERO;
    for p in points {
        let r = *p - center;
        inertia += (DMat3::IDENTITY * r.length_squared()
            - DMat3::from_cols(r * r.x, r * r.y, r * r.z))
            * m;
    }
    MassProperties {
        mass,
        center,
        inertia,
    }
}
