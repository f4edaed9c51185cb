// Overlay text quads from stb_easy_font: positions in window pixels from the top-left corner,
// colours as normalised bytes.
layout(location = 0) in vec2 pixel;
layout(location = 1) in vec4 vertexColour;
out vec4 textColour;
uniform vec2 viewportSize;

void main() {
  textColour = vertexColour;
  gl_Position = vec4(2.0 * pixel.x / viewportSize.x - 1.0, 1.0 - 2.0 * pixel.y / viewportSize.y, 0.0, 1.0);
}
