//! Principal axes of a body's inertia tensor: the symmetric eigen-decomposition
//! `I_body = V diag(I₁, I₂, I₃) Vᵀ`, by cyclic Jacobi rotations.
//!
//! Needed by the symplectic free-rotation map ([`super::free_rotation`]), which splits the
//! kinetic energy `Σ Π_k² / (2 I_k)` along principal axes; a mesh's inertia from Mirtich is
//! generally not diagonal in the mesh's axes.

use glam::{DMat3, DQuat, DVec3};

/// Principal moments in ascending order and the frame of their axes.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PrincipalAxes {
    /// I₁ ≤ I₂ ≤ I₃ (kg m²)
    pub moments: DVec3,
    /// body_from_principal: its columns are the principal axes in body coordinates
    /// (orthonormal, right-handed)
    pub frame: DMat3,
}

impl PrincipalAxes {
    /// The frame as a unit quaternion (body_from_principal).
    pub fn rotation(&self) -> DQuat {
        DQuat::from_mat3(&self.frame).normalize()
    }

    /// `V diag(I) Vᵀ`: the tensor back in body axes.
    pub fn reconstruct(&self) -> DMat3 {
        self.frame * DMat3::from_diagonal(self.moments) * self.frame.transpose()
    }
}

/// Eigen-decomposition of a symmetric 3×3 matrix (only the lower triangle's mirror is assumed:
/// `m` is symmetrised first). Cyclic Jacobi: each rotation zeroes one off-diagonal entry; the
/// off-diagonal mass falls quadratically, so a handful of sweeps reach rounding level.
pub fn principal_axes(m: DMat3) -> PrincipalAxes {
    let mut a = [[0.0f64; 3]; 3];
    for (r, row) in a.iter_mut().enumerate() {
        for (c, v) in row.iter_mut().enumerate() {
            *v = 0.5 * (m.col(c)[r] + m.col(r)[c]);
        }
    }
    let mut v = [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]];
    for _sweep in 0..32 {
        let off = a[0][1].abs() + a[0][2].abs() + a[1][2].abs();
        if off == 0.0 || !off.is_finite() {
            break;
        }
        for (p, q) in [(0, 1), (0, 2), (1, 2)] {
            let apq = a[p][q];
            if apq == 0.0 {
                continue;
            }
            // an entry too small to change either diagonal entry is rounding noise: drop it
            if a[p][p].abs() + 1e3 * apq.abs() == a[p][p].abs()
                && a[q][q].abs() + 1e3 * apq.abs() == a[q][q].abs()
            {
                a[p][q] = 0.0;
                a[q][p] = 0.0;
                continue;
            }
            // the rotation angle φ with tan 2φ = 2 a_pq / (a_qq − a_pp); t = tan φ, the
            // smaller root, so |φ| ≤ π/4 (the stable choice)
            let theta = (a[q][q] - a[p][p]) / (2.0 * apq);
            let t = if theta.abs() > 1e150 {
                0.5 / theta
            } else {
                theta.signum() / (theta.abs() + (theta * theta + 1.0).sqrt())
            };
            let c = 1.0 / (t * t + 1.0).sqrt();
            let s = t * c;
            // A ← Jᵀ A J and V ← V J with J the rotation in the (p, q) plane
            for row in &mut a {
                let (akp, akq) = (row[p], row[q]);
                row[p] = c * akp - s * akq;
                row[q] = s * akp + c * akq;
            }
            let (row_p, row_q) = (a[p], a[q]);
            for k in 0..3 {
                a[p][k] = c * row_p[k] - s * row_q[k];
                a[q][k] = s * row_p[k] + c * row_q[k];
            }
            a[p][q] = 0.0;
            a[q][p] = 0.0;
            for row in &mut v {
                let (vp, vq) = (row[p], row[q]);
                row[p] = c * vp - s * vq;
                row[q] = s * vp + c * vq;
            }
        }
    }
    // ascending moments, columns permuted to match
    let mut idx = [0usize, 1, 2];
    idx.sort_by(|&i, &j| a[i][i].total_cmp(&a[j][j]));
    let col = |k: usize| DVec3::new(v[0][k], v[1][k], v[2][k]);
    let (c0, c1) = (col(idx[0]), col(idx[1]));
    // right-handed: the third axis is the cross product (equal to ± the eigenvector)
    let c2 = if c0.cross(c1).dot(col(idx[2])) < 0.0 {
        -col(idx[2])
    } else {
        col(idx[2])
    };
    PrincipalAxes {
        moments: DVec3::new(a[idx[0]][idx[0]], a[idx[1]][idx[1]], a[idx[2]][idx[2]]),
        frame: DMat3::from_cols(c0, c1, c2),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn check(m: DMat3) -> PrincipalAxes {
        let pa = principal_axes(m);
        let scale = m.to_cols_array().iter().fold(0.0f64, |a, v| a.max(v.abs()));
        let rec = pa.reconstruct();
        for (x, y) in rec.to_cols_array().iter().zip(m.to_cols_array()) {
            assert!((x - y).abs() <= 1e-12 * scale, "{rec} vs {m}");
        }
        let vtv = pa.frame.transpose() * pa.frame;
        for (x, y) in vtv
            .to_cols_array()
            .iter()
            .zip(DMat3::IDENTITY.to_cols_array())
        {
            assert!((x - y).abs() <= 1e-14, "not orthonormal: {vtv}");
        }
        assert!((pa.frame.determinant() - 1.0).abs() < 1e-14, "left-handed");
        assert!(pa.moments.x <= pa.moments.y && pa.moments.y <= pa.moments.z);
        let q = DMat3::from_quat(pa.rotation());
        assert!(
            (q - pa.frame)
                .to_cols_array()
                .iter()
                .all(|d| d.abs() < 1e-14)
        );
        pa
    }

    #[test]
    fn diagonal_stays_put_and_is_sorted() {
        let pa = check(DMat3::from_diagonal(DVec3::new(1.0, 2.0, 3.0)));
        assert_eq!(pa.moments, DVec3::new(1.0, 2.0, 3.0));
        assert_eq!(pa.frame, DMat3::IDENTITY);
        let pa = check(DMat3::from_diagonal(DVec3::new(3.0, 1.0, 2.0)));
        assert_eq!(pa.moments, DVec3::new(1.0, 2.0, 3.0));
    }

    #[test]
    fn rotated_tensors_give_back_moments_and_axes() {
        for (angles, d) in [
            ((0.3, -1.1, 2.0), DVec3::new(1.0, 2.0, 3.0)),
            ((1.3, 0.2, -0.4), DVec3::new(5.0, 0.01, 40.0)),
            ((0.0, 0.7, 0.0), DVec3::new(2.0, 2.0, 7.0)),
            ((2.9, -0.3, 1.4), DVec3::new(1e-4, 3e-4, 2e-4)),
        ] {
            let r = DMat3::from_quat(DQuat::from_euler(
                glam::EulerRot::XYZ,
                angles.0,
                angles.1,
                angles.2,
            ));
            let m = r * DMat3::from_diagonal(d) * r.transpose();
            let pa = check(m);
            let mut sorted = d.to_array();
            sorted.sort_by(f64::total_cmp);
            let err = (pa.moments - DVec3::from_array(sorted)).abs().max_element();
            assert!(
                err <= 1e-14 * d.max_element(),
                "{} vs {sorted:?}",
                pa.moments
            );
        }
    }

    #[test]
    fn mirtich_tetrahedron_and_a_sphere() {
        let (d, o) = (1.0 / 80.0, 1.0 / 480.0);
        let tet = DMat3::from_cols(
            DVec3::new(d, o, o),
            DVec3::new(o, d, o),
            DVec3::new(o, o, d),
        );
        let pa = check(tet);
        // eigenvalues of d 𝟙 + o (𝟙𝟙ᵀ − 𝟙): d − o (twice) and d + 2o along (1, 1, 1)
        assert!((pa.moments - DVec3::new(d - o, d - o, d + 2.0 * o)).length() < 1e-17);
        let axis = pa.frame.col(2);
        assert!((axis.abs() - DVec3::splat(1.0 / 3f64.sqrt())).length() < 1e-14);
        check(DMat3::IDENTITY * 0.4);
    }
}
