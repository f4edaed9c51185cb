#include "render/ShaderSources.h"

#include <cmath>
#include <cstdio>

#include <map>
#include <stdexcept>

#include "render/EmbeddedShaders.h"
#include "render/GlContext.h"

namespace cloudlut::render {

const std::string& embeddedShaderFile(const std::string& name) {
  static const std::map<std::string, std::string> files = [] {
    std::map<std::string, std::string> m;
    for (const auto& f : embedded::kEmbeddedFiles) m.emplace(f.name, f.text);
    return m;
  }();
  const auto it = files.find(name);
  if (it == files.end()) throw GlError("shader file '" + name + "' was not embedded in this build");
  return it->second;
}

std::string glslDefine(const std::string& name, long long value) {
  return "#define " + name + " " + std::to_string(value) + "\n";
}

std::string glslFloatDefine(const std::string& name, float value) {
  // GLSL has no literal for an infinity or a NaN
  if (!std::isfinite(value)) throw std::invalid_argument("glslFloatDefine: " + name + " is not finite");
  char text[32];
  std::snprintf(text, sizeof text, "%.9g", static_cast<double>(value));
  std::string literal = text;
  if (literal.find_first_of(".eE") == std::string::npos) literal += ".0";  // a float literal, not an int
  return "#define " + name + " " + literal + "\n";
}

std::string assembleShader(const std::vector<std::string>& files, const std::string& defines) {
  // CLOUDLUT_FN is empty in GLSL (the shared files also default it themselves).
  std::string source = "#version 450 core\n#define CLOUDLUT_FN\n" + defines;
  for (std::size_t i = 0; i < files.size(); ++i) {
    source += "#line 1 " + std::to_string(i + 1) + "\n";
    source += embeddedShaderFile(files[i]);
    source += "\n";
  }
  return source;
}

std::string shaderFileLegend(const std::vector<std::string>& files) {
  std::string legend = "source string 0 is the preamble";
  for (std::size_t i = 0; i < files.size(); ++i)
    legend += ", " + std::to_string(i + 1) + " is " + files[i];
  return legend;
}

}  // namespace cloudlut::render
