// Detection of coplanar overlapping faces in different objects (scene/coplanar_overlap.h): the objects it flags
// get Scene's coplanar tie-break filter, the others none. It must flag every pair the filter would call a tie
// (else z-fighting speckle comes back: tests/robustness/coplanar_test.cpp renders those scenes) and should flag
// nothing else (else the filter costs time for nothing).
#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <cstdio>

#include "core/error.h"
#include "core/params.h"
#include "scene/coplanar_overlap.h"
#include "scene/scene.h"
#include "test_helpers.h"

namespace candela::test {
namespace {

/// Faces grouped into objects, in the layout Scene hands to find_coplanar_rivals.
struct Soup {
    std::vector<float> positions;
    std::vector<uint32_t> triangles;
    std::vector<CoplanarObject> objects;

    uint32_t vertex(Vec3 p) {
        positions.insert(positions.end(), {p.x, p.y, p.z});
        return uint32_t(positions.size() / 3 - 1);
    }
    void triangle(Vec3 a, Vec3 b, Vec3 c) { triangles.insert(triangles.end(), {vertex(a), vertex(b), vertex(c)}); }
    /// Appends the parallelogram p0 + [0,1]·e1 + [0,1]·e2 (two faces) to the open object.
    void quad(Vec3 p0, Vec3 e1, Vec3 e2) {
        triangle(p0, p0 + e1, p0 + e1 + e2);
        triangle(p0, p0 + e1 + e2, p0 + e2);
    }
    void begin_object(const Affine& to_world = Affine()) {
        const uint32_t t = uint32_t(triangles.size() / 3);
        objects.push_back({t, t, to_world});
    }
    void end_object() { objects.back().tri_end = uint32_t(triangles.size() / 3); }
    /// One object holding one quad.
    void quad_object(Vec3 p0, Vec3 e1, Vec3 e2, const Affine& to_world = Affine()) {
        begin_object(to_world);
        quad(p0, e1, e2);
        end_object();
    }
    CoplanarReport find(size_t max_triangles = size_t(1) << 22) const {
        return find_coplanar_rivals(positions.data(), triangles.data(), objects, max_triangles);
    }
};

std::vector<uint8_t> flags(std::initializer_list<int> v) { return std::vector<uint8_t>(v.begin(), v.end()); }

TEST(CoplanarOverlap, OverlappingCoplanarQuadsInTwoObjectsAreFlagged) {
    Soup s;
    s.quad_object(Vec3(-1.f, -1.f, -2.f), Vec3(1.3f, 0, 0), Vec3(0, 3.f, 0));
    s.quad_object(Vec3(-0.3f, -1.f, -2.f), Vec3(1.3f, 0, 0), Vec3(0, 3.f, 0));
    s.quad_object(Vec3(-1.f, -1.f, -3.f), Vec3(2.f, 0, 0), Vec3(0, 2.f, 0));  // a parallel quad behind: no rival
    EXPECT_EQ(s.find().flagged, flags({1, 1, 0}));
}

// Esc during the scene build reaches the detection too: a cancelled token makes it throw Cancelled (before any
// face is compared), and an untouched token changes nothing.
TEST(CoplanarOverlap, ACancelledTokenStopsTheDetection) {
    Soup s;
    s.quad_object(Vec3(-1.f, -1.f, -2.f), Vec3(1.3f, 0, 0), Vec3(0, 3.f, 0));
    s.quad_object(Vec3(-0.3f, -1.f, -2.f), Vec3(1.3f, 0, 0), Vec3(0, 3.f, 0));
    CancelToken token;
    EXPECT_EQ(find_coplanar_rivals(s.positions.data(), s.triangles.data(), s.objects, size_t(1) << 22, &token).flagged,
              flags({1, 1}));
    token.cancel();
    EXPECT_THROW(find_coplanar_rivals(s.positions.data(), s.triangles.data(), s.objects, size_t(1) << 22, &token),
                 Cancelled);
}

TEST(CoplanarOverlap, FacesTurnedAwayFromEachOtherStillOverlap) {
    // A double-sided plane built from two objects back to back z-fights just the same.
    Soup s;
    s.quad_object(Vec3(0.f, 0.f, 1.f), Vec3(1.f, 0, 0), Vec3(0, 1.f, 0));
    s.quad_object(Vec3(0.2f, 0.2f, 1.f), Vec3(0, 0.5f, 0), Vec3(0.5f, 0, 0));  // wound the other way
    EXPECT_EQ(s.find().flagged, flags({1, 1}));
}

// Faces are filed under one of ±n, chosen by the sign of n·g for a fixed direction g; for a plane containing g
// rounding can give a face and its rival opposite signs. Here the two faces' normals are tilted 1e-5 toward +g and
// −g (within the normal allowance of 1e-4; their far corners 1e-5 off each other's plane, within 2·2.1e-5·S with
// S ≈ 2): they must still meet.
TEST(CoplanarOverlap, FacesInAPlaneAlongTheSignDirectionStillMeet) {
    const Vec3 g = normalize(Vec3(0.5377f, 0.7031f, 0.4652f));  // coplanar_overlap.cpp's direction
    const Vec3 n0 = normalize(cross(g, Vec3(0.f, 0.f, 1.f))), w = cross(n0, g);
    const Vec3 p = n0 * 1.5f;
    Soup s;
    for (const float sign : {1.f, -1.f}) {
        const Vec3 e1 = g + n0 * (sign * 1e-5f);
        const Vec3 n = cross(e1, w);  // n0 − sign·1e-5·g
        ASSERT_LT(sign * dot(n, g), 0.f) << "the faces must fall on opposite sides of g";
        s.quad_object(p + g * (sign > 0.f ? 0.f : 0.3f), e1, w);
    }
    EXPECT_EQ(s.find().flagged, flags({1, 1}));
}

TEST(CoplanarOverlap, CoplanarButDisjointOrTouchingQuadsAreNotFlagged) {
    Soup s;
    s.quad_object(Vec3(0.f, 0.f, 1.f), Vec3(1.f, 0, 0), Vec3(0, 1.f, 0));
    s.quad_object(Vec3(1.5f, 0.f, 1.f), Vec3(1.f, 0, 0), Vec3(0, 1.f, 0));  // 0.5 beside it
    s.quad_object(Vec3(0.f, 1.f, 1.f), Vec3(1.f, 0, 0), Vec3(0, 1.f, 0));   // sharing its top edge
    // Diagonal neighbours: the boxes of the two triangles nearest to each other overlap, the triangles do not.
    s.begin_object();
    s.triangle(Vec3(1.f, 0.9f, 1.f), Vec3(1.1f, 0.f, 1.f), Vec3(1.1f, 0.9f, 1.f));
    s.end_object();
    s.begin_object();
    s.triangle(Vec3(0.f, 0.f, 1.f), Vec3(0.95f, 0.f, 1.f), Vec3(0.f, -1.f, 1.f));  // below the first quad
    s.end_object();
    const CoplanarReport r = s.find();
    EXPECT_EQ(r.flagged, flags({0, 0, 0, 0, 0}));
    EXPECT_FALSE(r.fallback);
}

// Planes 1e-3 apart (the scene's magnitude S is ~3 here, so 3e-4 S) are distinct: the exact test's threshold is
// 2·k_coplanar_detect_distance·S = 4.2e-5·S, 8× below. A gap of half the filter's own tie tolerance at these
// coordinates (k_coplanar_ulps·S/2: a pair the filter calls a tie) must be flagged.
TEST(CoplanarOverlap, ParallelPlanesApartAreNotFlaggedButTiesAre) {
    const float S = 3.f;
    for (const float gap : {1e-3f, 0.5f * k_coplanar_ulps * S}) {
        Soup s;
        s.quad_object(Vec3(-1.f, -1.f, -S), Vec3(2.f, 0, 0), Vec3(0, 2.f, 0));
        s.quad_object(Vec3(-0.5f, -0.5f, -S + gap), Vec3(2.f, 0, 0), Vec3(0, 2.f, 0));
        const int expected = gap < 1e-3f ? 1 : 0;
        EXPECT_EQ(s.find().flagged, flags({expected, expected})) << "gap " << gap;
    }
}

TEST(CoplanarOverlap, TwoTrianglesOfOneMeshAreNeverRivals) {
    Soup s;
    s.begin_object();
    s.quad(Vec3(0.f, 0.f, 1.f), Vec3(1.f, 0, 0), Vec3(0, 1.f, 0));    // adjacent triangles
    s.quad(Vec3(0.2f, 0.2f, 1.f), Vec3(1.f, 0, 0), Vec3(0, 1.f, 0));  // even overlapping ones, in one object
    s.end_object();
    s.quad_object(Vec3(5.f, 5.f, 1.f), Vec3(1.f, 0, 0), Vec3(0, 1.f, 0));  // a second object, elsewhere
    EXPECT_EQ(s.find().flagged, flags({0, 0}));
}

// coplanar_test.cpp's placements (scale, offset from the origin) and its rotated quads: the rotation and the shift
// to camera-world space (minus the camera position, in float, as Scene does) make the two quads' corners
// coplanar only up to rounding. Also its room with an emissive quad in the ceiling plane: the ceiling and the
// quad are flagged, the walls (which meet the ceiling only along edges) are not.
struct Placement {
    float scale;
    Vec3 offset;
};
const Placement k_placements[] = {
    {1e-3f, Vec3(0.f)}, {1.f, Vec3(0.f)}, {1e3f, Vec3(0.f)}, {1.f, Vec3(3e4f, -2e4f, 1e4f)}};

Affine placed(float scale, float roll, Vec3 offset, Vec3 camera) {
    const float c = std::cos(roll), s = std::sin(roll);
    const float rows[16] = {c * scale, -s * scale, 0,     offset.x, s * scale, c * scale, 0, offset.y,
                            0,         0,          scale, offset.z, 0,         0,         0, 1};
    Affine xf = Affine::from_rows(rows);
    for (int r = 0; r < 3; ++r) xf.m[r][3] -= camera[r];  // camera-world space, rounded in float
    return xf;
}

TEST(CoplanarOverlap, RotatedQuadsFarFromTheOriginAreFlagged) {
    for (const Placement& pl : k_placements)
        for (const float roll : {0.f, 0.5f, 0.3f})
            for (const Vec3 eye : {Vec3(0.f), Vec3(0.f, 1.8f, -1.5f)}) {
                const Affine xf = placed(pl.scale, roll, pl.offset, pl.offset + eye * pl.scale);
                Soup s;
                s.quad_object(Vec3(-1.f, -1.f, -2.f), Vec3(1.3f, 0, 0), Vec3(0, 3.f, 0), xf);
                s.quad_object(Vec3(-0.3f, -1.f, -2.f), Vec3(1.3f, 0, 0), Vec3(0, 3.f, 0), xf);
                // And a copy of the first 1e-3 (of the quads' size) in front: distinct.
                s.quad_object(Vec3(-1.f, -1.f, -2.f + 1e-3f), Vec3(1.3f, 0, 0), Vec3(0, 1.f, 0), xf);
                EXPECT_EQ(s.find().flagged, flags({1, 1, 0})) << "scale " << pl.scale << " roll " << roll;
            }
}

TEST(CoplanarOverlap, EmitterInTheRotatedRoomCeilingIsFlaggedAndTheWallsAreNot) {
    for (const Placement& pl : k_placements)
        for (const float roll : {0.f, 0.4f}) {
            // coplanar_test.cpp's Room, rotated about z by `roll`, seen from its camera position.
            const Affine xf = placed(pl.scale, roll, pl.offset, pl.offset);
            Soup s;
            s.quad_object(Vec3(-1.5f, 1.f, -4.f), Vec3(3.f, 0, 0), Vec3(0, 0, 5.f), xf);     // ceiling
            s.quad_object(Vec3(-1.5f, -1.f, -4.f), Vec3(0, 0, 5.f), Vec3(3.f, 0, 0), xf);    // floor
            s.quad_object(Vec3(-1.5f, -1.f, -4.f), Vec3(3.f, 0, 0), Vec3(0, 2.f, 0), xf);    // far wall
            s.quad_object(Vec3(-1.5f, -1.f, 1.f), Vec3(0, 2.f, 0), Vec3(3.f, 0, 0), xf);     // behind the camera
            s.quad_object(Vec3(-1.5f, -1.f, -4.f), Vec3(0, 2.f, 0), Vec3(0, 0, 5.f), xf);    // left
            s.quad_object(Vec3(1.5f, -1.f, -4.f), Vec3(0, 0, 5.f), Vec3(0, 2.f, 0), xf);     // right
            s.quad_object(Vec3(-0.4f, 1.f, -2.9f), Vec3(0.8f, 0, 0), Vec3(0, 0, 0.8f), xf);  // emitter
            EXPECT_EQ(s.find().flagged, flags({1, 0, 0, 0, 0, 0, 1})) << "scale " << pl.scale << " roll " << roll;
        }
}

TEST(CoplanarOverlap, InstancesAreComparedInWorldSpaceAndTooManyFacesFlagEverything) {
    // One mesh (a quad) placed twice, the second shifted half its width within the plane: the placements overlap.
    Soup s;
    s.quad_object(Vec3(0.f, 0.f, 0.f), Vec3(1.f, 0, 0), Vec3(0, 1.f, 0),
                  placed(1.f, 0.f, Vec3(0.f, 0.f, -2.f), Vec3(0.f)));
    s.objects.push_back(s.objects[0]);
    s.objects[1].to_world = placed(1.f, 0.2f, Vec3(0.5f, 0.f, -2.f), Vec3(0.f));
    s.quad_object(Vec3(0.f, 0.f, 0.f), Vec3(1.f, 0, 0), Vec3(0, 1.f, 0),
                  placed(1.f, 0.f, Vec3(0.f, 0.f, -5.f), Vec3(0.f)));
    EXPECT_EQ(s.find().flagged, flags({1, 1, 0}));
    const CoplanarReport capped = s.find(5);  // 6 faces in all
    EXPECT_TRUE(capped.fallback);
    EXPECT_EQ(capped.flagged, flags({1, 1, 1}));
}

// A large case in one piece: two 200×200-quad grids (160k faces) meeting along an edge, and a decal lying on one:
// only the decal and its grid are flagged. And how long that takes (printed, for the record).
TEST(CoplanarOverlap, LargeGridsMeetingAlongAnEdgeAndADecal) {
    Soup s;
    const int n = 200;
    const float cell = 1.f / n;
    for (int g = 0; g < 2; ++g) {
        s.begin_object();
        for (int i = 0; i < n; ++i)
            for (int j = 0; j < n; ++j) s.quad(Vec3(g + i * cell, j * cell, -2.f), Vec3(cell, 0, 0), Vec3(0, cell, 0));
        s.end_object();
    }
    s.quad_object(Vec3(1.3f, 0.3f, -2.f), Vec3(0.25f, 0, 0), Vec3(0, 0.25f, 0));
    const auto t0 = std::chrono::steady_clock::now();
    const CoplanarReport r = s.find();
    const double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
    std::printf("coplanar detection: %zu faces in %.1f ms (%zu exact tests)\n", r.triangles, ms, r.exact_tests);
    EXPECT_EQ(r.flagged, flags({0, 1, 1}));
}

// Through Scene: the flags reach SceneStats (and so the filter), a scene without coplanar rivals has none.
TEST(CoplanarOverlap, SceneCountsTheObjectsThatGetTheFilter) {
    for (const bool overlap : {false, true}) {
        MeshBuilder b;
        const uint32_t m = b.add_material(Color(0.8f), Color(0.f));
        b.add_instance(b.add_quad_z(-1.f, 0.3f, -1.f, 1.f, -2.f, m));
        b.add_instance(b.add_quad_z(overlap ? -0.3f : 0.3f, 1.f, -1.f, 1.f, -2.f, m));
        b.add_instance(b.add_box(Vec3(0.2f), m));
        const SceneArrays arrays = b.arrays();
        const Scene scene(arrays, basic_params(8, 8, 1, 1), nullptr);
        EXPECT_EQ(scene.stats().coplanar_objects, overlap ? 2u : 0u);
    }
}

}  // namespace
}  // namespace candela::test

namespace candela::test {
namespace {}  // namespace
}  // namespace candela::test
