/* SLEEF 3.5's pure-C scalar names (what csrc/base/dmath.h calls) over
 * SLEEF 3.3's scalar functions, for the Windows build (tools/win/deps.sh
 * says why 3.3: it is the SLEEF source these machines can download).
 * Not bit-identical to 3.5.1: a stand-in until its source is reachable. */
#define SLEEF_STATIC_LIBS /* libsleef.a, not a DLL */
#include <sleef.h>

double Sleef_sind1_u35purec(double x) { return Sleef_sin_u35(x); }
double Sleef_cosd1_u35purec(double x) { return Sleef_cos_u35(x); }
double Sleef_tand1_u35purec(double x) { return Sleef_tan_u35(x); }
double Sleef_asind1_u35purec(double x) { return Sleef_asin_u35(x); }
double Sleef_acosd1_u35purec(double x) { return Sleef_acos_u35(x); }
double Sleef_atan2d1_u35purec(double y, double x) { return Sleef_atan2_u35(y, x); }
double Sleef_expd1_u10purec(double x) { return Sleef_exp_u10(x); }
double Sleef_logd1_u35purec(double x) { return Sleef_log_u35(x); }
double Sleef_cbrtd1_u35purec(double x) { return Sleef_cbrt_u35(x); }
double Sleef_hypotd1_u35purec(double x, double y) { return Sleef_hypot_u35(x, y); }
double Sleef_powd1_u10purec(double x, double y) { return Sleef_pow_u10(x, y); }
