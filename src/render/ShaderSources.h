#pragma once
// The renderer's GLSL, embedded in the binary at build time (cmake/EmbedFiles.cmake): the shared
// lut_formats/glsl files verbatim, the clipmap grid functions of src/scene/glsl and
// src/render/shaders. A program's source is "#version 450 core", the `#define`s of the C++ that
// sizes its buffers and dispatches it, then each file preceded by a #line directive whose
// source-string number is its position in the list, so that compiler messages can be traced back
// ("2:LINE" → the second file).
#include <string>
#include <vector>

namespace cloudlut::render {

// The embedded file of that name (e.g. "cloudlut_sampling.glsl"); throws GlError if absent.
const std::string& embeddedShaderFile(const std::string& name);

// "#define NAME VALUE\n": a constant that C++ and GLSL share, injected by the C++ that owns it.
std::string glslDefine(const std::string& name, long long value);
// The same for a float, written so that GLSL reads back the same float (9 significant digits);
// std::invalid_argument for a value that is not finite, which GLSL cannot write.
std::string glslFloatDefine(const std::string& name, float value);

// A complete program source from embedded files, after `defines` (e.g. glslDefine("STAGE", 1)).
std::string assembleShader(const std::vector<std::string>& files, const std::string& defines = "");

// The value of uProbePasses for programs that include shaders/loop_budget.glsl (whether the GL
// cut an invocation's loops short: a loop of this many passes then makes fewer).
inline constexpr int kLoopProbePasses = 2;

// "source string 0 is the preamble, 1 is FILE, ..." for a program's sources, for error messages.
std::string shaderFileLegend(const std::vector<std::string>& files);

}  // namespace cloudlut::render
