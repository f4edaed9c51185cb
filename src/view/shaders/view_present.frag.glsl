// The displayed frame: an sRGB-encoded RGBA8 texture whose row 0 is the top of the picture
// (render::Image's order), so that v is flipped.
in vec2 uv;
out vec4 colour;
uniform sampler2D frame;

void main() { colour = vec4(texture(frame, vec2(uv.x, 1.0 - uv.y)).rgb, 1.0); }
