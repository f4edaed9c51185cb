#pragma once
// The renderer's GLSL, embedded in the binary at build time (cmake/EmbedFiles.cmake): the shared
// lut_formats/glsl files verbatim, the clipmap grid functions of src/scene/glsl and
// src/render/shaders.
#include <string>
#include <vector>

namespace cloudlut::render {

// The embedded file of that name (e.g. "cloudlut_sampling.glsl"); throws GlError if absent.
const std::string& embeddedShaderFile(const std::string& name);

// Complete sources of the particle program: "#version 450 core", then each file preceded by
// a #line directive whose source-string number is its position in the list below, so that
// compiler messages can be traced back ("0:LINE" → file 0 ...).
std::string particleVertexSource();
std::string particleFragmentSource();

// "file number N is NAME" for a program's sources, for error messages.
std::string shaderFileLegend(bool fragment);

// A program assembled from embedded files the same way, after `defines` (e.g. "#define STAGE 1\n").
std::string assembleShader(const std::vector<std::string>& files, const std::string& defines = "");
std::string shaderFileLegend(const std::vector<std::string>& files);

}  // namespace cloudlut::render
