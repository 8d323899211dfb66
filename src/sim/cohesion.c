/* Cohesion laws (PHYSICS 2.4). */
#include <config.h>
#include "cohesion.h"
#include <math.h>
double mimas_jkr_force(double w, double E, double R, double d)
{ return d > 0 ? sqrt(4 * M_PI * w * E) * pow(R * d, 0.75) : 0; }
double mimas_jkr_delta_min(double w, double E, double R)
{ return pow(2.25 * M_PI * w / E * sqrt(R), 2.0 / 3.0); }
double mimas_bridge_half_angle(const mimas_bridge *b, double r, double s)
{ double a = pow(b->volume / (0.96 * r * r * r * (1 + 6 * s / (2 * r)) * (1 + 1.1 * sin(b->theta))), 0.25);
  return a >= 1 ? M_PI / 2 : asin(a); }
double mimas_bridge_rupture_distance(const mimas_bridge *b)
{ return (1 + b->theta / 2) * cbrt(b->volume); }
double mimas_bridge_force(const mimas_bridge *b, double r, double s)
{ if (s < 0) s = 0; if (s > mimas_bridge_rupture_distance(b)) return 0;
  double be = mimas_bridge_half_angle(b, r, s), th = b->theta;
  double R1 = (r * (1 - cos(be)) + s / 2) / cos(be + th), R2 = r * sin(be) - R1 * (1 - sin(be + th));
  double pk = b->gamma * (1 / R1 - 1 / R2);
  return 2 * M_PI * b->gamma * r * sin(be) * sin(be + th) + M_PI * r * r * pk * sin(be) * sin(be); }
