#pragma once
// The shared GLSL (lut_formats/glsl) compiled as C++ through GLM: one definition of the
// parameterization and of the phase functions for the baker, the CLI, the tests and the shaders.
#include "cloudlut_glsl.hpp"
