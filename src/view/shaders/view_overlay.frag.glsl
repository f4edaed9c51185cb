in vec4 textColour;
out vec4 colour;

void main() { colour = textColour; }
