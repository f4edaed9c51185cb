// sky_textures.glsl — how the sky pass's shaders sample the atmosphere's tables: each table is
// uploaded as a 3D texture of depth 1 (the renderer's one texture path), so the shared GLSL's
// AtmosphereTexture is a sampler3D here. Precedes cloudlut_atmosphere_tables.glsl.
#define CLOUDLUT_ATMOSPHERE_TEXTURE_DEFINED
#define AtmosphereTexture sampler3D
vec3 atmosphereTexture(sampler3D table, vec2 uv) { return texture(table, vec3(uv, 0.5)).rgb; }
