// Eigenvalues and unit eigenvectors of a symmetric 3 x 3 matrix by cyclic Jacobi rotations, on
// host and device, in float or double: the surface's anisotropic kernels (surface/anisotropy.h)
// and a mesh body's principal axes of inertia (scene/mesh_solid.h).
#pragma once

#include <cmath>

#include "core/config.h"

namespace weir {

// a: the matrix, overwritten (its diagonal ends as the eigenvalues); vectors: set to the
// eigenvectors, vector k in column k (vectors[row][k]). Stops after `sweeps` sweeps or once the
// off-diagonal part's square is under `tolerance` times the diagonal's. Converges quadratically.
template <class T>
WEIR_HD inline void jacobiEigen(T a[3][3], T vectors[3][3], int sweeps, T tolerance) {
    for (int r = 0; r < 3; ++r) {
        for (int c = 0; c < 3; ++c) {
            vectors[r][c] = r == c ? T(1) : T(0);
        }
    }
    for (int sweep = 0; sweep < sweeps; ++sweep) {
        const T off = a[0][1] * a[0][1] + a[0][2] * a[0][2] + a[1][2] * a[1][2];
        const T diagonal = a[0][0] * a[0][0] + a[1][1] * a[1][1] + a[2][2] * a[2][2];
        if (!(off > tolerance * diagonal)) {
            break;
        }
        for (int p = 0; p < 2; ++p) {
            for (int q = p + 1; q < 3; ++q) {
                if (a[p][q] == T(0)) {
                    continue;
                }
                // The rotation in the (p, q) plane that zeroes a[p][q].
                const T theta = (a[q][q] - a[p][p]) / (T(2) * a[p][q]);
                const T t = (theta >= 0 ? T(1) : T(-1)) /
                            (std::fabs(theta) + std::sqrt(theta * theta + T(1)));
                const T c = T(1) / std::sqrt(t * t + T(1));
                const T s = t * c;
                for (int k = 0; k < 3; ++k) {  // a <- a J (columns p, q)
                    const T akp = a[k][p], akq = a[k][q];
                    a[k][p] = c * akp - s * akq;
                    a[k][q] = s * akp + c * akq;
                }
                for (int k = 0; k < 3; ++k) {  // a <- J^T a (rows p, q)
                    const T apk = a[p][k], aqk = a[q][k];
                    a[p][k] = c * apk - s * aqk;
                    a[q][k] = s * apk + c * aqk;
                }
                for (int k = 0; k < 3; ++k) {  // vectors <- vectors J
                    const T vkp = vectors[k][p], vkq = vectors[k][q];
                    vectors[k][p] = c * vkp - s * vkq;
                    vectors[k][q] = s * vkp + c * vkq;
                }
            }
        }
    }
}

}  // namespace weir
