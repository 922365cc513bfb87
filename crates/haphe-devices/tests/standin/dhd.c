/* A stand-in for the Force Dimension SDK's libdhd.so, for haphe's tests: the functions
 * haphe calls, with dhdc.h's C signatures, over a simulated mechanism whose end point
 * follows a scripted trajectory (one sample per dhdGetPosition call), recording every
 * force written. Test-only symbols (standin_*) script it and read it back. */
#include <stdlib.h>
#include <string.h>

#include "env.h"

#define STANDIN_MAX 400000
#define DHD_ERROR_COM 5

static double samples[STANDIN_MAX][6]; /* position, velocity, metres and m/s */
static int n_samples = 0;
static int current = -1;
static double forces[STANDIN_MAX][3];
static int n_forces = 0;
static int fail_from = -1;  /* dhdGetPosition call from which the device is unplugged */
static int devices = 1;
static int opened = 0;
static int force_enabled = 0;
static int last_error = 0;
static int calls = 0;

void standin_reset(int device_count) {
  n_samples = 0; current = -1; n_forces = 0; fail_from = -1; devices = device_count;
  opened = 0; force_enabled = 0; last_error = 0; calls = 0; n_button_masks = 0;
}
int standin_set_path(const double *pv, int n) {
  if (n > STANDIN_MAX) n = STANDIN_MAX;
  memcpy(samples, pv, sizeof(double) * 6 * (size_t)n);
  n_samples = n;
  return n;
}
void standin_fail_from(int call) { fail_from = call; }
int standin_forces(double *out, int max) {
  int n = n_forces < max ? n_forces : max;
  memcpy(out, forces, sizeof(double) * 3 * (size_t)n);
  return n_forces;
}
int standin_force_enabled(void) { return force_enabled; }
int standin_opened(void) { return opened; }

int dhdGetDeviceCount(void) { return devices; }
int dhdOpen(void) {
  if (devices < 1) { last_error = DHD_ERROR_COM; return -1; }
  opened = 1;
  int n = standin_env_path(samples, STANDIN_MAX);
  if (n >= 0) { n_samples = n; current = -1; n_forces = 0; calls = 0; }
  return 0;
}
int dhdClose(char id) {
  (void)id;
  standin_env_report(forces, n_forces, STANDIN_MAX, force_enabled);
  opened = 0;
  return 0;
}
const char *dhdGetSystemName(char id) { (void)id; return opened ? "stand-in omega.3" : NULL; }
int dhdEnableForce(unsigned char val, char id) { (void)id; force_enabled = val; return 0; }
int dhdGetPosition(double *px, double *py, double *pz, char id) {
  (void)id;
  if (!opened) { last_error = DHD_ERROR_COM; return -1; }
  if (fail_from >= 0 && calls >= fail_from) { last_error = DHD_ERROR_COM; return -1; }
  calls++;
  if (current + 1 < n_samples) current++;
  if (current < 0) { *px = *py = 0.0; *pz = 1.0; return 0; }
  *px = samples[current][0]; *py = samples[current][1]; *pz = samples[current][2];
  return 0;
}
int dhdGetLinearVelocity(double *vx, double *vy, double *vz, char id) {
  (void)id;
  if (!opened) { last_error = DHD_ERROR_COM; return -1; }
  if (current < 0) { *vx = *vy = *vz = 0.0; return 0; }
  *vx = samples[current][3]; *vy = samples[current][4]; *vz = samples[current][5];
  return 0;
}
unsigned int dhdGetButtonMask(char id) { (void)id; return standin_buttons_at(current); }
int dhdSetForce(double fx, double fy, double fz, char id) {
  (void)id;
  if (!opened) { last_error = DHD_ERROR_COM; return -1; }
  if (n_forces < STANDIN_MAX) {
    forces[n_forces][0] = fx; forces[n_forces][1] = fy; forces[n_forces][2] = fz;
    n_forces++;
  }
  return 0;
}
double dhdGetMaxForce(char id) { (void)id; return 3.3; }
int dhdErrorGetLast(void) { return last_error; }
const char *dhdErrorGetStr(int error) {
  return error == DHD_ERROR_COM ? "communication error between the host and the haptic device" : "no error";
}
const char *dhdErrorGetLastStr(void) { return dhdErrorGetStr(last_error); }
