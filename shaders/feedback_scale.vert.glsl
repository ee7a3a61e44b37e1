// Transform-feedback smoke program: out = scale * in. Used by the GL foundation test to check that
// a context, an embedded shader and a feedback readback all work on the current driver.
layout(location = 0) in vec3 position;
uniform float scale;
out vec3 scaled;
void main() { scaled = scale * position; }
