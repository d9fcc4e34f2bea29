
/* banyan (tools/win/sleef_purec.c): SLEEF 3.5's pure-C scalar names that
 * csrc/base/dmath.h calls, over SLEEF 3.3's scalar functions. */
#ifdef __cplusplus
extern "C" {
#endif
double Sleef_sind1_u35purec(double x);
double Sleef_cosd1_u35purec(double x);
double Sleef_tand1_u35purec(double x);
double Sleef_asind1_u35purec(double x);
double Sleef_acosd1_u35purec(double x);
double Sleef_atan2d1_u35purec(double y, double x);
double Sleef_expd1_u10purec(double x);
double Sleef_logd1_u35purec(double x);
double Sleef_cbrtd1_u35purec(double x);
double Sleef_hypotd1_u35purec(double x, double y);
double Sleef_powd1_u10purec(double x, double y);
#ifdef __cplusplus
}
#endif
