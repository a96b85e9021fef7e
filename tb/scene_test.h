// SPDX-License-Identifier: Apache-2.0
// Helpers of the scene-reader tests, defined in test_scene_trace.cpp and shared by the
// other scene, 2D and text tests.
#pragma once

#include <gtest/gtest.h>

#include <functional>
#include <string>

#include "common/screen_vertex.h"
#include "ref/pipeline.h"
#include "ref/scene.h"

namespace rastsim::scene_test {

// Success when fn throws a SceneError whose message starts with `where` + " " (e.g.
// "t.trace:3:") and contains `phrase`.
::testing::AssertionResult SceneFails(const std::function<void()>& fn, const std::string& where,
                                      const std::string& phrase);
// The scene rendered by the reference pipeline with the default config.
RenderStats render_default(const Scene& scene);

// An OBJ octahedron of radius 5 about the origin (bounding-box centre 0, sphere radius
// 5): vertices on the axes (+x, -x, +y, -y, +z, -z), a front face (1 3 5, counter-clockwise
// seen from +z) and a back face (2 6 4).
inline constexpr const char* kOcta =
    "v 5 0 0\n"
    "v -5 0 0\n"
    "v 0 5 0\n"
    "v 0 -5 0\n"
    "v 0 0 5\n"
    "v 0 0 -5\n"
    "f 1 3 5\n"
    "f 2 6 4\n";

// The depth tests' hand-built triangles' vertices (common/screen_vertex.h).
using ::rastsim::screen_vertex;

}  // namespace rastsim::scene_test
