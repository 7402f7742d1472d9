// Reading a scene dump (docs/architecture.md): a directory with params.json and one NAME.npy per array.
#pragma once

#include <string>
#include <vector>

#include "core/params.h"
#include "input/scene_arrays.h"

namespace candela {

struct SceneDump {
    SceneArrays arrays;
    Params params;
    std::vector<std::string> warnings;  // unknown files and keys
};

/// Throws InvalidScene / InvalidParameter naming the file and what is wrong.
SceneDump read_scene_dump(const std::string& directory);

}  // namespace candela
