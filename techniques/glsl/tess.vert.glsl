// tess.vert.glsl — pass-through vertex stage of tess-displacement (S3).
layout(location = 0) in vec3 a_pos;
layout(location = 1) in vec3 a_nrm;
layout(location = 2) in vec2 a_uv;
layout(location = 3) in vec4 a_tan;
layout(location = 4) in vec2 a_seam_uv;    // UV and normal of the first vertex at this
layout(location = 5) in vec3 a_seam_nrm;   // position (render.c, mesh_canonical)

out GeomData {
    vec3 pos;
    vec3 nrm;
    vec2 uv;
    vec4 tan;
    vec2 seam_uv;
    vec3 seam_nrm;
} go;

void main()
{
    go.pos = a_pos;
    go.nrm = a_nrm;
    go.uv = a_uv;
    go.tan = a_tan;
    go.seam_uv = a_seam_uv;
    go.seam_nrm = a_seam_nrm;
}
