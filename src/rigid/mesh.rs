//! Closed triangle meshes: the shapes whose mass properties we compute. Loaded from OBJ
//! (positions and faces only) or built in code (boxes, lathed solids).

use crate::diag::Diagnostic;
use glam::DVec3;
use std::collections::HashMap;
use std::path::Path;

/// An indexed triangle mesh, counter-clockwise seen from outside (outward normals).
#[derive(Debug, Clone, PartialEq, Default)]
pub struct TriMesh {
    pub positions: Vec<DVec3>,
    pub triangles: Vec<[u32; 3]>,
}

impl TriMesh {
    pub fn new(positions: Vec<DVec3>, triangles: Vec<[u32; 3]>) -> Self {
        Self {
            positions,
            triangles,
        }
    }

    /// Corner positions of triangle `i`.
    pub fn triangle(&self, i: usize) -> [DVec3; 3] {
        let [a, b, c] = self.triangles[i];
        [
            self.positions[a as usize],
            self.positions[b as usize],
            self.positions[c as usize],
        ]
    }

    /// Axis-aligned bounds (min, max); zeros for an empty mesh.
    pub fn bounds(&self) -> (DVec3, DVec3) {
        if self.positions.is_empty() {
            return (DVec3::ZERO, DVec3::ZERO);
        }
        let mut lo = DVec3::splat(f64::INFINITY);
        let mut hi = DVec3::splat(f64::NEG_INFINITY);
        for p in &self.positions {
            lo = lo.min(*p);
            hi = hi.max(*p);
        }
        (lo, hi)
    }

    /// Every point moved by `offset`.
    pub fn translated(&self, offset: DVec3) -> Self {
        Self {
            positions: self.positions.iter().map(|p| *p + offset).collect(),
            triangles: self.triangles.clone(),
        }
    }

    /// Every point mapped by the 3×3 matrix `m` (a rotation keeps the mesh closed and outward).
    pub fn transformed(&self, m: glam::DMat3) -> Self {
        Self {
            positions: self.positions.iter().map(|p| m * *p).collect(),
            triangles: self.triangles.clone(),
        }
    }

    /// Checks the mesh is closed and consistently oriented: every directed edge (a, b) is
    /// matched by exactly one (b, a). Returns a message naming the first bad edge.
    pub fn check_closed(&self) -> Result<(), String> {
        if self.triangles.is_empty() {
            return Err("the mesh has no triangles".into());
        }
        let n = self.positions.len() as u32;
        let mut edges: HashMap<(u32, u32), i32> = HashMap::new();
        for (t, tri) in self.triangles.iter().enumerate() {
            for k in 0..3 {
                let (a, b) = (tri[k], tri[(k + 1) % 3]);
                if a >= n || b >= n {
                    return Err(format!("triangle {t} indexes vertex {} of {n}", a.max(b)));
                }
                *edges.entry((a, b)).or_default() += 1;
            }
        }
        for (&(a, b), &count) in &edges {
            let back = edges.get(&(b, a)).copied().unwrap_or(0);
            if count != 1 || back != 1 {
                return Err(format!(
                    "edge {a}-{b} is used {count} time(s) one way and {back} the other: \
                     the mesh is not closed and consistently oriented"
                ));
            }
        }
        Ok(())
    }

    /// Parses OBJ text: `v x y z` and `f i j k ...` lines (polygons are fan-triangulated,
    /// `i/t/n` and negative indices accepted); everything else is ignored.
    pub fn parse_obj(text: &str, file: &Path) -> Result<Self, Diagnostic> {
        let mut positions = Vec::new();
        let mut triangles = Vec::new();
        for (line_no, line) in text.lines().enumerate() {
            let line_no = line_no + 1;
            let content = line.split('#').next().unwrap_or("");
            let mut words = content.split_whitespace();
            let col_of = |w: &str| w.as_ptr() as usize - line.as_ptr() as usize + 1;
            match words.next() {
                Some("v") => {
                    let mut xyz = [0.0f64; 3];
                    for (i, slot) in xyz.iter_mut().enumerate() {
                        let Some(w) = words.next() else {
                            return Err(Diagnostic::new(
                                file,
                                line_no,
                                line.len() + 1,
                                format!("vertex needs 3 coordinates, found {i}"),
                            ));
                        };
                        *slot = match w.parse::<f64>() {
                            Ok(v) if v.is_finite() => v,
                            _ => {
                                return Err(Diagnostic::new(
                                    file,
                                    line_no,
                                    col_of(w),
                                    format!("`{w}` is not a finite number"),
                                ));
                            }
                        };
                    }
                    positions.push(DVec3::from_array(xyz));
                }
                Some("f") => {
                    let mut idx = Vec::new();
                    for w in words {
                        let first = w.split('/').next().unwrap_or("");
                        let bad = |msg: String| Diagnostic::new(file, line_no, col_of(w), msg);
                        let i: i64 = first
                            .parse()
                            .map_err(|_| bad(format!("`{w}` is not a vertex index")))?;
                        let n = positions.len() as i64;
                        let resolved = if i > 0 { i - 1 } else { n + i };
                        if i == 0 || resolved < 0 || resolved >= n {
                            return Err(bad(format!(
                                "vertex index {i} is out of range (1..={n} defined so far)"
                            )));
                        }
                        idx.push(resolved as u32);
                    }
                    if idx.len() < 3 {
                        return Err(Diagnostic::new(
                            file,
                            line_no,
                            1,
                            "a face needs at least 3 vertices",
                        ));
                    }
                    for k in 1..idx.len() - 1 {
                        triangles.push([idx[0], idx[k], idx[k + 1]]);
                    }
                }
                _ => {}
            }
        }
        if triangles.is_empty() {
            return Err(Diagnostic::whole_file(file, "no faces found"));
        }
        Ok(Self {
            positions,
            triangles,
        })
    }

    /// Reads and parses an OBJ file.
    pub fn load_obj(path: &Path) -> Result<Self, Diagnostic> {
        let text = crate::project_files::read_to_string(path)
            .map_err(|e| Diagnostic::whole_file(path, format!("cannot read: {e}")))?;
        Self::parse_obj(&text, path)
    }

    /// OBJ text of this mesh (1-based indices).
    pub fn to_obj(&self) -> String {
        let mut s = String::new();
        for p in &self.positions {
            s.push_str(&format!("v {} {} {}\n", p.x, p.y, p.z));
        }
        for t in &self.triangles {
            s.push_str(&format!("f {} {} {}\n", t[0] + 1, t[1] + 1, t[2] + 1));
        }
        s
    }

    /// An axis-aligned box from `min` to `max`, 12 triangles.
    pub fn cuboid(min: DVec3, max: DVec3) -> Self {
        let positions = (0..8)
            .map(|i| {
                DVec3::new(
                    if i & 1 == 0 { min.x } else { max.x },
                    if i & 2 == 0 { min.y } else { max.y },
                    if i & 4 == 0 { min.z } else { max.z },
                )
            })
            .collect();
        // quads (outward, counter-clockwise seen from outside)
        let quads = [
            [0, 4, 6, 2], // -x
            [1, 3, 7, 5], // +x
            [0, 1, 5, 4], // -y
            [2, 6, 7, 3], // +y
            [0, 2, 3, 1], // -z
            [4, 5, 7, 6], // +z
        ];
        let mut triangles = Vec::new();
        for q in quads {
            triangles.push([q[0], q[1], q[2]]);
            triangles.push([q[0], q[2], q[3]]);
        }
        Self {
            positions,
            triangles,
        }
    }

    /// A box of the given full side lengths centred at the origin.
    pub fn centred_box(size: DVec3) -> Self {
        Self::cuboid(-size / 2.0, size / 2.0)
    }

    /// The tetrahedron (0, e_x, e_y, e_z).
    pub fn corner_tetrahedron() -> Self {
        Self {
            positions: vec![DVec3::ZERO, DVec3::X, DVec3::Y, DVec3::Z],
            triangles: vec![[0, 2, 1], [0, 1, 3], [0, 3, 2], [1, 2, 3]],
        }
    }

    /// A solid of revolution about +y: `profile` lists (radius, y) from bottom to top, radii
    /// > 0; the ends are closed by fans to points on the axis. `segments` ≥ 3.
    pub fn lathe(profile: &[(f64, f64)], segments: usize) -> Self {
        let segments = segments.max(3);
        let mut positions = Vec::new();
        for &(r, y) in profile {
            for s in 0..segments {
                let a = std::f64::consts::TAU * s as f64 / segments as f64;
                positions.push(DVec3::new(r * a.cos(), y, -r * a.sin()));
            }
        }
        let ring = |i: usize, s: usize| (i * segments + s % segments) as u32;
        let mut triangles = Vec::new();
        for i in 0..profile.len().saturating_sub(1) {
            for s in 0..segments {
                let (a, b) = (ring(i, s), ring(i, s + 1));
                let (c, d) = (ring(i + 1, s), ring(i + 1, s + 1));
                triangles.push([a, b, d]);
                triangles.push([a, d, c]);
            }
        }
        let bottom = positions.len() as u32;
        positions.push(DVec3::new(0.0, profile.first().map_or(0.0, |p| p.1), 0.0));
        let top = positions.len() as u32;
        positions.push(DVec3::new(0.0, profile.last().map_or(0.0, |p| p.1), 0.0));
        let last = profile.len().saturating_sub(1);
        for s in 0..segments {
            triangles.push([bottom, ring(0, s + 1), ring(0, s)]);
            triangles.push([top, ring(last, s), ring(last, s + 1)]);
        }
        Self {
            positions,
            triangles,
        }
    }

    /// A buoy: a cylinder with a cone on top and a short cone below (about 1.2 m tall).
    pub fn buoy() -> Self {
        Self::lathe(
            &[
                (0.15, -0.45),
                (0.4, -0.25),
                (0.4, 0.25),
                (0.25, 0.5),
                (0.05, 0.75),
            ],
            24,
        )
    }

    /// A bottle: a body, shoulder and neck (about 0.3 m tall).
    pub fn bottle() -> Self {
        Self::lathe(
            &[
                (0.035, -0.15),
                (0.04, -0.14),
                (0.04, 0.05),
                (0.032, 0.08),
                (0.015, 0.11),
                (0.013, 0.14),
                (0.015, 0.15),
            ],
            20,
        )
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn generated_meshes_are_closed() {
        TriMesh::centred_box(DVec3::new(1.0, 2.0, 3.0))
            .check_closed()
            .unwrap();
        TriMesh::corner_tetrahedron().check_closed().unwrap();
        TriMesh::buoy().check_closed().unwrap();
        TriMesh::bottle().check_closed().unwrap();
    }

    #[test]
    fn an_open_mesh_is_reported() {
        let mut m = TriMesh::centred_box(DVec3::ONE);
        m.triangles.pop();
        assert!(m.check_closed().is_err());
    }

    #[test]
    fn obj_errors_name_line_and_column() {
        let e = TriMesh::parse_obj("v 0 0 0\nv 1 x 0\n", Path::new("m.obj")).unwrap_err();
        assert_eq!((e.line, e.col), (2, 5));
        let e = TriMesh::parse_obj("v 0 0 0\nf 1 2 3\n", Path::new("m.obj")).unwrap_err();
        assert_eq!((e.line, e.col), (2, 5));
    }

    #[test]
    fn obj_round_trips() {
        let m = TriMesh::buoy();
        let back = TriMesh::parse_obj(&m.to_obj(), Path::new("b.obj")).unwrap();
        assert_eq!(back.triangles, m.triangles);
        assert_eq!(back.positions.len(), m.positions.len());
    }
}
