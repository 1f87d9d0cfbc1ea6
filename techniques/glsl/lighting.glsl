// lighting.glsl — the one lighting file.  Model by #define:
//   LIGHTING_LAMBERT | LIGHTING_PHONG | LIGHTING_BLINN_PHONG (default) |
//   LIGHTING_COOK_TORRANCE (Beckmann D, Schlick F, S3 geometric term G);
//   TOKSVIG_ON scales the Phong/Blinn-Phong exponent by the Toksvig factor;
//   SPECULAR_MAP_ON scales every specular term by lighting_spec_k, which the
//   fragment stage sets from the material's specular map.
// Point lights; no light where N.L <= 0.  Attenuation by #define:
//   ATTENUATION_INVERSE_QUADRATIC (default) 1/(c + l*d + q*d^2) with u_atten
//   ATTENUATION_S1                           max(0, 1 - d^2/r^2), r = u_light_radius (S1)
//   ATTENUATION_NONE                         1
#include "common.glsl"

#if !defined(LIGHTING_LAMBERT) && !defined(LIGHTING_PHONG) && !defined(LIGHTING_COOK_TORRANCE)
#define LIGHTING_BLINN_PHONG
#endif

uniform vec3 u_light_color[MAX_LIGHTS];
uniform vec3 u_atten;        // (c, l, q)
uniform vec3 u_ambient;
uniform float u_shininess;   // Phong / Blinn-Phong exponent n
uniform float u_f0;          // Cook-Torrance Fresnel reflectance at normal incidence
uniform float u_roughness;   // Cook-Torrance Beckmann slope m
uniform float u_light_radius;   // r of ATTENUATION_S1

float lighting_attenuation(float d)
{
#if defined(ATTENUATION_S1)
    return max(0.0, 1.0 - (d * d) / (u_light_radius * u_light_radius));
#elif defined(ATTENUATION_NONE)
    return 1.0;
#else
    return 1.0 / (u_atten.x + u_atten.y * d + u_atten.z * d * d);
#endif
}

const float LIGHTING_PI = 3.14159265;

#ifdef SPECULAR_MAP_ON
float lighting_spec_k = 1.0;   // the specular map at the shaded point
#endif

// Specular term for unit n, v, l; nlen = length of the filtered normal
// before renormalisation (Toksvig), 1 when unknown.
float lighting_specular(vec3 n, vec3 v, vec3 l, float nlen)
{
#if defined(LIGHTING_PHONG) || defined(LIGHTING_BLINN_PHONG)
    float e = u_shininess, s = 1.0;
#ifdef TOKSVIG_ON
    float len = clamp(nlen, 1e-3, 1.0);
    float ft = len / (len + e * (1.0 - len));
    s = (1.0 + ft * e) / (1.0 + e);
    e = ft * e;
#endif
#ifdef LIGHTING_PHONG
    return s * pow(max(dot(reflect(-l, n), v), 0.0), e);
#else
    return s * pow(max(dot(n, normalize(l + v)), 0.0), e);
#endif
#elif defined(LIGHTING_COOK_TORRANCE)
    vec3 h = normalize(l + v);
    float nh = max(dot(n, h), 1e-4), nv = max(dot(n, v), 1e-4);
    float nl = max(dot(n, l), 1e-4), vh = max(dot(v, h), 1e-4);
    float m2 = u_roughness * u_roughness, nh2 = nh * nh;
    float d = exp((nh2 - 1.0) / (m2 * nh2)) / (LIGHTING_PI * m2 * nh2 * nh2);
    float f = u_f0 + (1.0 - u_f0) * pow(1.0 - vh, 5.0);
    float g = min(1.0, min(2.0 * nh * nv / vh, 2.0 * nh * nl / vh));
    return d * f * g / (4.0 * nv);   // (D F G / (4 N.V N.L)) * N.L
#else
    return 0.0;                      // Lambert
#endif
}

// Contribution of one light: lvec = surface -> light (unnormalised).
vec3 lighting_light(vec3 n, vec3 v, vec3 lvec, vec3 color, vec3 albedo, float nlen)
{
    float d = length(lvec);
    vec3 l = lvec / max(d, 1e-6);
    float nl = dot(n, l);
    if (nl <= 0.0)
        return vec3(0.0);
    float att = lighting_attenuation(d);
#ifdef SPECULAR_MAP_ON
    return color * att * (albedo * nl + vec3(lighting_spec_k * lighting_specular(n, v, l, nlen)));
#else
    return color * att * (albedo * nl + vec3(lighting_specular(n, v, l, nlen)));
#endif
}
