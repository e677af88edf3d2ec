/*
 * cclouds/rain.h -- one raindrop: Beard-Chuang shape, terminal speed, refraction masks, drop pixel colour and the
 * light-drop model (rr §2.1, §2.2, §3.1, §3.2; after Rousseau, Jolivet & Ghazanfarpour, "Realistic real-time rain
 * rendering", Computers & Graphics 30, 2006; shape from Beard & Chuang, J. Atmos. Sci. 44, 1987).
 *
 * Frames and units (every function):
 *   - Drop frame: y up (the fall axis), the drop axisymmetric about y. The Beard-Chuang angle theta is measured from
 *     the DOWNWARD vertical (theta = 0 points down, theta = pi up); phi is the azimuth about y from +x towards +z.
 *     Lengths in mm; a is the radius of the Beard-Chuang reference sphere (rr-eq1), the four table rows
 *     a = 0.5, 1.0, 3.0, 4.5 mm.
 *   - Mask frame (rr-alg-3.1.1): a drop seen from the side by parallel rays. x to the right, y up, z ALONG the viewing
 *     direction (away from the viewer) -- the encoding of the text's shaders, whose test `refract.z > 0` keeps rays
 *     that go on into the scene. Texel (u, v) in [-1, 1]^2 (u right, v up) is the point (u L, v L) of the drop's
 *     vertical mid-plane, L = ccl_rain_drop_extent (mm) for the outline/exact methods and L = a for the sphere.
 *     Texel (i, j) of a size x size mask (row i from the top) has u = 2 (j + 0.5)/size - 1, v = 1 - 2 (i + 0.5)/size.
 *     From mask to camera space (OpenGL, looking down -z) for a billboard facing view direction f:
 *     w = x r + y u + z f with r = normalize(f x (0, 1, 0)), u = r x f.
 *   - Capture texture (rr-alg-3.1.2): an RGB float image, rows from the top, uv in [0, 1]^2 with u to the right and v
 *     DOWN, taken from the viewer with a perspective camera of vertical field of view fov (tan_half_fov = tan(fov/2))
 *     and aspect width/height; edges clamped (GL_CLAMP_TO_EDGE).
 *
 * Readings chosen where the text is silent (each also a named parameter in Python):
 *   - rr-eq1 / rr-tab-2.1: interp CCL_RAIN_INTERP_TABLE accepts only the four tabulated radii (others give NaN);
 *     CCL_RAIN_INTERP_LINEAR interpolates each coefficient linearly in a between rows, a in [0.5, 4.5]. The text has
 *     no rows for 1.5, 2, 2.5 mm: interpolating is an assumption.
 *   - rr-tab-2.2: linear between the 23 rows; below the first row (0.1 mm) Stokes' law v = 0.72 (r / 0.1)^2 m/s;
 *     from 4 mm on the plateau 9.23 m/s; divided by `slowdown` (the application's 4, rr §5.2.2).
 *   - rr-A1: DistFact(d) = 1 / (1 + (d / r_half)^2), an inverse-square fall-off with a finite core (1 at the light,
 *     1/2 at the half-intensity distance r_half).
 */
#ifndef CCLOUDS_RAIN_H
#define CCLOUDS_RAIN_H

#include "cclouds/common.h"

#ifdef __cplusplus
extern "C" {
#endif

#define CCL_RAIN_SHAPE_ROWS 4       /* rows of Table 2.1: a = 0.5, 1.0, 3.0, 4.5 mm */
#define CCL_RAIN_SHAPE_TERMS 11     /* C_0 ... C_10 */
#define CCL_RAIN_SPEED_ROWS 23      /* rows of Table 2.2 */
#define CCL_RAIN_MASK_SIZE 512      /* the text's mask and capture size (rr §3.1.1, §3.1.2) */
#define CCL_RAIN_APP_SLOWDOWN 4     /* the application's slow-down of the terminal speeds (rr §5.2.2) */
#define CCL_RAIN_MASK_MAX_REFLECTIONS 3 /* exact trace: internal reflections followed before giving up */
#define CCL_RAIN_TRACE_STEPS 64     /* exact trace: march steps per surface search */
#define CCL_RAIN_TRACE_BISECTIONS 32 /* exact trace: bisection steps per surface hit */

/* How a drop radius between (or off) the rows of Table 2.1 is handled. */
typedef enum ccl_rain_interp {
    CCL_RAIN_INTERP_TABLE = 0,  /* only a = 0.5, 1.0, 3.0, 4.5 mm (else NaN) */
    CCL_RAIN_INTERP_LINEAR = 1  /* coefficients linear in a between rows; a in [0.5, 4.5] */
} ccl_rain_interp;

/* How the refraction mask is computed (rr-alg-3.1.1). */
typedef enum ccl_rain_mask_method {
    CCL_RAIN_MASK_SPHERE = 0,   /* a sphere (the Cg `refract` alternative of the text; a circle outline) */
    CCL_RAIN_MASK_OUTLINE = 1,  /* the application: Beard-Chuang outline, refraction of the sphere stretched onto it */
    CCL_RAIN_MASK_EXACT = 2     /* beyond the text: rays traced through both surfaces of the Beard-Chuang drop */
} ccl_rain_mask_method;

/* Where the refracted capture pixel P_c is looked up (rr-alg-3.1.3). */
typedef enum ccl_rain_mapping {
    CCL_RAIN_MAPPING_OFFSET = 0, /* the shader: P_c = P_o + refract.xy / refract.z, scaled to capture uv */
    CCL_RAIN_MAPPING_PROJECT = 1 /* exact: the exit direction rotated to camera space and projected */
} ccl_rain_mapping;

/* Capture texture filtering (rr §3.1.2 says nearest suffices, the FBO code sets GL_LINEAR). */
typedef enum ccl_rain_filter {
    CCL_RAIN_FILTER_NEAREST = 0,
    CCL_RAIN_FILTER_LINEAR = 1
} ccl_rain_filter;

/* --- drop shape --------------------------------------------------------------------------------------------------- */

/* Beard-Chuang shape coefficient C_n = (Table 2.1 entry) x 1e-4 for a drop of radius a.
 * Ref: rr-tab-2.1 (Beard & Chuang 1987, via Rousseau et al. 2006). n -> n in [0, 10]; a -> a [mm]: with
 * CCL_RAIN_INTERP_TABLE one of 0.5, 1.0, 3.0, 4.5 (others give NaN), with CCL_RAIN_INTERP_LINEAR in [0.5, 4.5]
 * (others give NaN).
 * Output: C_n, |C_n| < 0.3. */
CCL_API float ccl_rain_drop_coefficient(int n, float a, ccl_rain_interp interp);

/* Beard-Chuang equilibrium drop shape r(theta) = a (1 + sum_{n=0}^{10} C_n cos(n theta)).
 * Ref: rr-eq1. theta -> theta [rad] in [0, pi], 0 = pointing down; a -> a [mm] (see ccl_rain_drop_coefficient for
 * interp). Output: r [mm] > 0; a = 1: r(0) = 0.9277, r(pi/2) = 1.0236, r(pi) = 0.9683. */
CCL_API float ccl_rain_drop_radius(float theta, float a, ccl_rain_interp interp);

/* Point and outward unit normal of the axisymmetric 3-D drop surface:
 *   p = r(theta) (sin theta cos phi, -cos theta, sin theta sin phi),
 *   meridian normal (r sin theta - r' cos theta, -(r cos theta + r' sin theta)) revolved by phi, normalised,
 *   r'(theta) = -a sum n C_n sin(n theta).
 * Ref: rr-eq1 (the 3-D surface; rr §2.1). theta in [0, pi], phi [rad] any, a and interp as above.
 * Returns p [mm]; writes the unit normal to *out_normal. */
CCL_API ccl_vec3 ccl_rain_drop_surface(float theta, float phi, float a, ccl_rain_interp interp,
                                       ccl_vec3 *out_normal);

/* Volume of the drop, V = (2 pi / 3) int_0^pi r(theta)^3 sin(theta) d theta (Simpson, 128 intervals, rel. error
 * < 1e-6). Ref: rr-eq1. a, interp as above. Output: V [mm^3] (close to 4/3 pi a^3: a is the equal-volume radius). */
CCL_API float ccl_rain_drop_volume(float a, ccl_rain_interp interp);

/* Axis ratio of the drop, height / width = (r(0) + r(pi)) / (2 max_theta r(theta) sin theta) (the maximum over 1025
 * samples of theta; rel. error < 2e-6). Ref: rr-eq1. a, interp as above. Output in (0, 1] (1 = sphere); 0.926 for
 * a = 1 mm, 0.641 for a = 3 mm, 0.511 for 4.5 mm. */
CCL_API float ccl_rain_drop_axis_ratio(float a, ccl_rain_interp interp);

/* Half-size of the drop's mask and billboard: a bound of max_theta r(theta) (the maximum over 65 samples plus the
 * sampling error bound a (pi/64)^2 / 8 sum n^2 |C_n|, so the drop always fits; equals a for a sphere).
 * Ref: rr-alg-3.1.1. a, interp as above. Output: L [mm] >= max r. */
CCL_API float ccl_rain_drop_extent(float a, ccl_rain_interp interp);

/* --- terminal speed ----------------------------------------------------------------------------------------------- */

/* Terminal fall speed of a raindrop from Table 2.2 (23 rows; spherical drops up to 0.45 mm, ellipsoidal from 0.5 mm),
 * divided by slowdown: linear between rows, Stokes v = 0.72 (r/0.1)^2 below r = 0.1 mm, the plateau 9.23 m/s from
 * r = 4 mm (the table reaches it at 2.75 mm).
 * Ref: rr-tab-2.2 (Gunn & Kinzer 1949 via Rousseau et al. 2006). radius_mm -> drop radius [mm] in [0, 10];
 * slowdown -> divisor in [1/64, 1000] (1 = physical, CCL_RAIN_APP_SLOWDOWN = 4 the application's; the lower bound
 * keeps the speed finite).
 * Output: speed [m/s] / slowdown, in [0, 9.23 / slowdown], non-decreasing in the radius. */
CCL_API float ccl_rain_terminal_speed(float radius_mm, float slowdown);

/* --- refraction masks --------------------------------------------------------------------------------------------- */

/* One texel of the refraction mask: the direction in which the view ray through (u, v) leaves the drop.
 * The ray travels along +z of the mask frame (parallel rays: the drop is tiny), refracts into the water (rr-snell),
 * crosses the drop and refracts out (total internal reflection: reflected and traced on, up to
 * CCL_RAIN_MASK_MAX_REFLECTIONS times, then the direction (0, 0, 0), the text's "no refraction").
 * method SPHERE: the unit sphere (a, deform, interp ignored; L = a). method OUTLINE: inside the Beard-Chuang outline
 * r <= r(theta) (the drop's mid-plane), refraction of the unit sphere at the point rescaled radially by 1 / r(theta)
 * (the application's simplification, spec error index item 12). method EXACT: ray traced through both surfaces of
 * the Beard-Chuang drop (march CCL_RAIN_TRACE_STEPS, bisect CCL_RAIN_TRACE_BISECTIONS).
 * Ref: rr-alg-3.1.1 (rr §3.1.1, Obrazek 3.4). u, v in [-1, 1] (mask frame above); a [mm] as above; deform in [0, 1]
 * scales every C_n (0 = a sphere, 1 = Beard-Chuang); n_water -> relative index in [1, 2] (1.33).
 * Returns the unit exit direction (mask frame; (0,0,0) outside or when no exit); writes the outward unit normal at the
 * entry point (z < 0: towards the viewer; (0,0,0) outside) and *out_inside (1 inside the outline, else 0). */
CCL_API ccl_vec3 ccl_rain_mask_texel(float u, float v, float a, float deform, float n_water, ccl_rain_interp interp,
                                     ccl_rain_mask_method method, ccl_vec3 *out_normal, int *out_inside);

/* The whole size x size mask: out_rgba[(i size + j) 4 + c] = (exit x, y, z, inside) of texel (i, j) (row i from the
 * top); out_normals (may be NULL) [(i size + j) 3 + c] the entry normal. Ref: rr-alg-3.1.1. size in [1, 4096];
 * other arguments as ccl_rain_mask_texel. Returns CCL_EINVAL (nothing written) for an argument out of its domain. */
CCL_API ccl_status ccl_rain_mask(int size, float a, float deform, float n_water, ccl_rain_interp interp,
                                 ccl_rain_mask_method method, float *out_rgba, float *out_normals);

/* --- drop pixel colour -------------------------------------------------------------------------------------------- */

/* P_i -> P_o -> P_c: where the capture texture is read for a drop pixel.
 *   P_o = capture uv of the undeviated view direction c (camera space):
 *         (0.5 + s_x c.x / (-c.z), 0.5 - s_y c.y / (-c.z)),  s_x = 0.5 / (tan_half_fov aspect), s_y = 0.5 / tan_half_fov;
 *   mapping OFFSET (the shader rr-code-5.2.3): P_c = P_o + (s_x e.x / e.z, -s_y e.y / e.z);
 *   mapping PROJECT: w = e.x r + e.y u + e.z f (billboard frame about f = c), P_c = the capture uv of w.
 * The two agree for a drop at the centre of the view. valid = 0 when c or w points backwards (c.z >= 0, w.z >= 0) or
 * e.z <= 0 (the shader's test); P_c = P_o = (0, 0) then.
 * Ref: rr-alg-3.1.3 (rr §3.1.3, Obrazek 3.5). view_dir -> c, unit, from the eye through P_i (camera space, OpenGL);
 * exit_dir -> e, the mask texel (mask frame); tan_half_fov in [1/64, 100]; aspect in [1/64, 100] (s_x <= 2048).
 * Returns P_c (uv, may leave [0, 1]^2: the capture is clamped); writes *out_p_o and *out_valid. A direction at 90 deg
 * to the view axis projects to infinity: where e.z > 0 (or -c.z > 0, w.z < 0) is below ~1e-38 of the other
 * components, P_c (P_o) overflows to +-Inf, NaN where two such infinities cancel. */
CCL_API ccl_vec2 ccl_rain_refracted_uv(ccl_vec3 view_dir, ccl_vec3 exit_dir, float tan_half_fov, float aspect,
                                       ccl_rain_mapping mapping, ccl_vec2 *out_p_o, int *out_valid);

/* Colour of the capture texture rgb (width x height x 3 floats, rows from the top) at uv, nearest or bilinear
 * (texel centres at (j + 0.5)/width), edges clamped. Not a catalogue entry (a texture fetch). */
CCL_API ccl_vec3 ccl_rain_sample_capture(const float *rgb, int width, int height, ccl_vec2 uv, ccl_rain_filter filter);

/* One drop billboard, rr-alg-3.1: for each of out_size x out_size pixels (u, v) (mask-frame coordinates): the mask
 * texel (nearest), outside -> (0,0,0,0); inside -> P_i's view direction normalize(f + tan(angular_radius)(u r + v up))
 * (billboard frame about f = centre_dir), P_c by ccl_rain_refracted_uv, colour fetched from the capture, alpha 1
 * (black with alpha 1 where no refracted ray exists, as the shader's zero colour).
 * Ref: rr-alg-3.1. capture: cap_w x cap_h x 3 floats; mask: mask_size^2 x 4 floats (ccl_rain_mask); centre_dir unit
 * (camera space); angular_radius [rad] in (0, 0.5]; out_rgba: out_size^2 x 4 floats. CCL_EINVAL on bad input. */
CCL_API ccl_status ccl_rain_shade_drop(const float *capture, int cap_w, int cap_h, const float *mask, int mask_size,
                                       ccl_vec3 centre_dir, float angular_radius, float tan_half_fov, float aspect,
                                       ccl_rain_mapping mapping, ccl_rain_filter filter, int out_size,
                                       float *out_rgba);

/* Error of the single capture taken from the viewer (rr-alg-3.2.2): the angle between the direction e leaving a
 * drop at p and the direction from the viewer (origin) to the background point the drop really sees, with the
 * background a sphere of radius R around the viewer.  s = -p.e + sqrt((p.e)^2 - |p|^2 + R^2), q = p + s e,
 * angle = atan2(|e x q|, e.q).
 * Ref: rr-alg-3.2.2. p [scene units]; e unit; R > 0 (any: a radius whose square is not a normal float, beyond
 * 2^+-60, is divided out of p first, the angle being scale-free). Output: [rad] in [0, pi], ~ |p| sin(angle(p, e)) / R
 * for a far background; NaN where |p| >= R (the drop is not inside the background). */
CCL_API float ccl_rain_capture_parallax(ccl_vec3 p, ccl_vec3 e, float R);

/* --- light-drop interaction (described by the text, never implemented in it) ------------------------------------- */

/* A1 = C_L DistFact (V_P->E . V_N): the largest colour change a light can give the pixel.
 * DistFact = 1 / (1 + (dist / r_half)^2). variant CORRECTED: the dot product clamped at 0 (a normal facing away from
 * the eye gets nothing); THESIS: unclamped as printed (spec error index item 9).
 * Ref: rr-A1. c_l -> C_L (RGB, >= 0); dist -> pixel-light distance >= 0; v_pe -> unit direction pixel -> eye;
 * v_n -> unit normal; r_half -> half-intensity distance > 0 (same unit as dist). Output: RGB. */
CCL_API ccl_vec3 ccl_rain_light_a1(ccl_vec3 c_l, float dist, ccl_vec3 v_pe, ccl_vec3 v_n, float r_half,
                                   ccl_variant variant);

/* A2 = max(0, V_P->L . V_N): external reflection back towards the light.
 * Ref: rr-A2. v_pl -> unit direction pixel -> light; v_n -> unit normal. Output in [0, 1]. */
CCL_API float ccl_rain_light_a2(ccl_vec3 v_pl, ccl_vec3 v_n);

/* A3 = max(0, (-V_PL_2D . V_N_2D) (1 - (-V_PL . V_N))): rays leaving up or down after internal reflections; the 2-D
 * vectors are the horizontal (x, z) projections, normalised. Guard: a projection shorter than 1e-6 (a vertical
 * vector, where the plane of incidence is undefined) makes the horizontal factor 0.
 * Ref: rr-A3. v_pl, v_n unit, drop frame (y up). Output in [0, 2]. */
CCL_API float ccl_rain_light_a3(ccl_vec3 v_pl, ccl_vec3 v_n);

/* Final drop pixel colour with two point lights: C_F = C_O C_amb + sum_{k=1,2} A1_k (A2_k + A3_k) (component-wise),
 * A1..A3 evaluated from the positions (V_P->E = normalize(eye - p), V_P->L = normalize(light - p), dist = |light - p|).
 * A light of colour (0, 0, 0) is off. No output clamp (none is specified).
 * Ref: rr-CF (with rr-A1, rr-A2, rr-A3). c_o -> C_O refracted colour; c_amb -> ambient colour; p, eye, l1, l2 ->
 * positions (drop frame, y up); n -> unit normal at p; c_l1, c_l2 -> light colours >= 0; r_half, variant as
 * ccl_rain_light_a1. Output: RGB >= 0 (corrected variant). */
CCL_API ccl_vec3 ccl_rain_light_colour(ccl_vec3 c_o, ccl_vec3 c_amb, ccl_vec3 p, ccl_vec3 n, ccl_vec3 eye, ccl_vec3 l1,
                                       ccl_vec3 c_l1, ccl_vec3 l2, ccl_vec3 c_l2, float r_half, ccl_variant variant);

#ifdef __cplusplus
}
#endif

#endif /* CCLOUDS_RAIN_H */
