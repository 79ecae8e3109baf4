/* material: the three surface kinds of the scenes (Lambertian, perfect mirror,
 * clear dielectric glass) and their optics: reflection, refraction, Fresnel,
 * cosine-weighted sampling. */
#ifndef PM_MATERIAL_H
#define PM_MATERIAL_H

#include "vec.h"

typedef enum { MATERIAL_LAMBERT = 0, MATERIAL_MIRROR = 1, MATERIAL_GLASS = 2 } material_kind;

#define MATERIAL_NAME_MAX 64

/* A material as the scene file defines it. */
typedef struct {
    material_kind kind;
    vec3 color;  /* Lambert: reflectance rho; mirror: reflectance; glass: unused (1) */
    double ior;  /* glass: index of refraction (outside is 1) */
    char name[MATERIAL_NAME_MAX];
} material;

/* "lambert", "mirror", "glass". */
const char *material_kind_name(material_kind k);
/* Mirror direction of d about unit normal n. */
vec3 material_reflect(vec3 d, vec3 n);
/* Unpolarised Fresnel reflectance for a ray with cosine cos_i (> 0) to the
 * normal going from index n1 into n2. Returns 1 past the critical angle. */
double material_fresnel(double cos_i, double n1, double n2);
/* Refraction of unit d through a surface with unit normal n facing against d
 * (dot(d, n) < 0), relative index eta = n1/n2. Returns 0 on total internal
 * reflection, else 1 with *out the unit refracted direction. */
int material_refract(vec3 d, vec3 n, double eta, vec3 *out);
/* The two branches of a glass surface with index ior, hit by unit d against
 * unit normal n from outside (front) or inside: returns the Fresnel weight
 * of reflection, 1 on total internal reflection; *can_refract says whether
 * *refr (the refracted direction) was set. */
double material_glass_split(vec3 d, vec3 n, int front, double ior, vec3 *refr, int *can_refract);
/* Cosine-weighted direction about unit n from two uniforms in [0,1). */
vec3 material_sample_cosine(vec3 n, double u1, double u2);

#endif
