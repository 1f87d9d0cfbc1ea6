//@technique hang
// as good as endless: llvmpipe ends every loop after 65535 iterations, so
// each iteration does 64 fetches (about 4e6 per pixel, minutes a frame)
#define HANG_FETCH4(o) s += height_at(uv + (o)) + height_at(uv - (o)) + height_at(uv + (o).yx) + height_at(uv - (o).yx);
#define HANG_FETCH16(o) HANG_FETCH4(o) HANG_FETCH4(o * 2.0) HANG_FETCH4(o * 3.0) HANG_FETCH4(o * 4.0)
vec3 user_surface(vec2 uv, vec3 v)
{
    float s = 0.0;
    for (int i = 0; i < 1000000000; i++) {
        vec2 o = vec2(float(i) * 1e-4, s * 1e-6);
        HANG_FETCH16(o) HANG_FETCH16(o * 5.0) HANG_FETCH16(o * 7.0) HANG_FETCH16(o * 11.0)
    }
    return vec3(uv, s);
}
