// mesh/check_resolution.h — the exact verdict R1-R4 of resolve.h on given positions (the
// building block of ResolveReport::resolved, for tests and independent checks).
//
// Inputs   meshes A0 and B0 at rest (or A0 alone: self-contact), their positions a1 and b1 to
//          judge, the fixed flags per vertex, QualityLimits (R4's bounds, defaults in the struct).
// Outputs  a ResolveReport with r1 to r4, resolved, limits, remaining_pairs, bad_elements,
//          poor_elements, moved_fixed_vertices, skipped and the volume and shape ratios filled.
#pragma once

#include <vector>

#include "pdd/mesh/mesh.h"
#include "pdd/mesh/resolve.h"
#include "pdd/pdd.h"

namespace pdd::mesh {

// The exact verdict on given positions (the building block of report.resolved, for tests and
// independent checks): R1 over every pair (fresh broadphase, exact decision), R2 per element
// against its rest orientation (exact sign of the determinant), R3 for the fixed flags given,
// R4 per element for `limits` (exact); check_resolution_self: A0 alone, self-contact. Fills r1 to r4, resolved,
// limits, remaining_pairs, bad_elements, poor_elements, moved_fixed_vertices, skipped and the
// volume and shape ratios. Throws std::invalid_argument for limits outside (0, 1].
ResolveReport check_resolution(const Mesh& A0, const std::vector<Vec3d>& a1, const Mesh& B0,
                               const std::vector<Vec3d>& b1,
                               const std::vector<char>& fixed_a = {},
                               const std::vector<char>& fixed_b = {},
                               const QualityLimits& limits = {});
ResolveReport check_resolution_self(const Mesh& A0, const std::vector<Vec3d>& a1,
                                    const std::vector<char>& fixed_a = {},
                                    const QualityLimits& limits = {});

}  // namespace pdd::mesh
