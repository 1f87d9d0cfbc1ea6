// broken.frag.glsl — deliberately invalid (technique debug-broken-shader):
// proves that a compile failure is reported with the driver's info log.
out vec4 o_color;
void main()
{
    o_color = undefined_symbol_for_testing * 2.0;
}
