// Affine transforms (3×4, row-major, as Blender's matrix_world rows) for points, vectors and normals.
#pragma once

#include "core/vec.h"

namespace candela {

struct Affine {
    float m[3][4] = {{1, 0, 0, 0}, {0, 1, 0, 0}, {0, 0, 1, 0}};

    /// From 16 floats of a row-major 4×4 matrix (the last row is ignored: affine only).
    static Affine from_rows(const float* rows16) {
        Affine a;
        for (int r = 0; r < 3; ++r)
            for (int c = 0; c < 4; ++c) a.m[r][c] = rows16[4 * r + c];
        return a;
    }

    Vec3 point(const Vec3& p) const {
        return {m[0][0] * p.x + m[0][1] * p.y + m[0][2] * p.z + m[0][3],
                m[1][0] * p.x + m[1][1] * p.y + m[1][2] * p.z + m[1][3],
                m[2][0] * p.x + m[2][1] * p.y + m[2][2] * p.z + m[2][3]};
    }
    Vec3 vector(const Vec3& v) const {
        return {m[0][0] * v.x + m[0][1] * v.y + m[0][2] * v.z, m[1][0] * v.x + m[1][1] * v.y + m[1][2] * v.z,
                m[2][0] * v.x + m[2][1] * v.y + m[2][2] * v.z};
    }
    Vec3 column(int c) const { return {m[0][c], m[1][c], m[2][c]}; }
    Vec3 translation() const { return column(3); }

    float determinant3() const {
        return m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1]) - m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0]) +
               m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0]);
    }

    /// The inverse transform (the 3×3 part must be invertible).
    Affine inverse() const {
        const Affine cof = normal_matrix();  // cofactors: inverse = cofactorᵀ / det
        const float inv_det = 1.f / determinant3();
        Affine r;
        for (int i = 0; i < 3; ++i)
            for (int j = 0; j < 3; ++j) r.m[i][j] = cof.m[j][i] * inv_det;
        const Vec3 t = r.vector(translation());
        for (int i = 0; i < 3; ++i) r.m[i][3] = -t[i];
        return r;
    }
    /// The transpose of the 3×3 part applied to v (world → object for normals, up to scale).
    Vec3 transpose_vector(const Vec3& v) const {
        return {m[0][0] * v.x + m[1][0] * v.y + m[2][0] * v.z, m[0][1] * v.x + m[1][1] * v.y + m[2][1] * v.z,
                m[0][2] * v.x + m[1][2] * v.y + m[2][2] * v.z};
    }

    /// Cofactor matrix of the 3×3 part: transforms normals (inverse transpose up to a positive factor
    /// det·(...)); keeps the normal's orientation consistent with the transformed winding.
    Affine normal_matrix() const {
        Affine n;
        const Vec3 c0 = column(0), c1 = column(1), c2 = column(2);
        const Vec3 r0 = cross(c1, c2), r1 = cross(c2, c0), r2 = cross(c0, c1);
        for (int i = 0; i < 3; ++i) {
            n.m[i][0] = r0[i];
            n.m[i][1] = r1[i];
            n.m[i][2] = r2[i];
            n.m[i][3] = 0.f;
        }
        return n;
    }
};

}  // namespace candela
