/* davit as an FMI 2.0 co-simulation FMU over the C ABI (include/davit.h).
 *
 * The FMU carries a deck and its data files in resources/ (deck.nml); fmi2DoStep advances
 * the launch to the communication point (davit_advance_to), the inputs act before it (a
 * winch speed set-point, reached at once; a hook release), and the outputs are read after
 * it. Variables (value references, modelDescription.xml):
 *   0-2  boat CG position x, y, z in the inertial frame (z down) [m]      output
 *   3-4  sling tensions at the fore and aft hooks [N]                      output
 *   5    waterborne time [s] (-1 before)                                   output
 *   6    hook release time [s] (-1 before)                                 output
 *   10   drum speed set-point [m/s] (pay-out > 0)                          input
 *   11   release the hooks (Boolean)                                       input
 * The FMU state is the C ABI's snapshot: a restore replays the run (doc/howto/library.md).
 * The FMI headers are those FMPy ships (fmpy/c-code), included at build time only. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "fmi2Functions.h"
#include "davit.h"

typedef struct {
  davit_handle h;
  fmi2CallbackFunctions cb;
  char *instance;
  char deck[4096];
  double winch, winch_set;
  int release, released;
} instance_t;

static void logmsg(instance_t *c, fmi2Status s, const char *msg) {
  if (c && c->cb.logger) c->cb.logger(c->cb.componentEnvironment, c->instance ? c->instance : "davit", s, "davit", "%s", msg);
}

static fmi2Status fail(instance_t *c, const char *what) {
  char buf[1024];
  if (!c->h) {
    char msg[256];
    snprintf(msg, sizeof msg, "%s: no run (call fmi2EnterInitializationMode first)", what);
    logmsg(c, fmi2Error, msg);
    return fmi2Error;
  }
  size_t n = davit_error_message(c->h, buf, sizeof buf);
  if (n >= sizeof buf) n = sizeof buf - 1;
  buf[n] = '\0';
  char msg[1200];
  snprintf(msg, sizeof msg, "%s: %s", what, buf);
  logmsg(c, fmi2Error, msg);
  return fmi2Error;
}

const char *fmi2GetTypesPlatform(void) { return fmi2TypesPlatform; }
const char *fmi2GetVersion(void) { return fmi2Version; }
fmi2Status fmi2SetDebugLogging(fmi2Component c, fmi2Boolean on, size_t n, const fmi2String cat[]) {
  (void)c; (void)on; (void)n; (void)cat;
  return fmi2OK;
}

/* resources/deck.nml from the resource URI file:///path/resources */
static int deck_path(const char *uri, char *out, size_t len) {
  const char *p = uri;
  if (!p) return 0;
  if (strncmp(p, "file://", 7) == 0) p += 7;
  if (strncmp(p, "localhost/", 10) == 0) p += 9;
  size_t n = strlen(p);
  while (n > 0 && p[n - 1] == '/') n--;
  if (n + 10 >= len) return 0;
  memcpy(out, p, n);
  strcpy(out + n, "/deck.nml");
  return 1;
}

fmi2Component fmi2Instantiate(fmi2String name, fmi2Type type, fmi2String guid,
                              fmi2String resources, const fmi2CallbackFunctions *cb,
                              fmi2Boolean visible, fmi2Boolean logging) {
  (void)guid; (void)visible; (void)logging;
  if (type != fmi2CoSimulation) return NULL;
  instance_t *c = calloc(1, sizeof *c);
  if (!c) return NULL;
  if (cb) c->cb = *cb;
  const char *nm = name ? name : "davit";
  c->instance = malloc(strlen(nm) + 1);
  if (c->instance) strcpy(c->instance, nm);
  c->winch = c->winch_set = -1.0;
  if (!deck_path(resources, c->deck, sizeof c->deck)) {
    logmsg(c, fmi2Error, "no resource location");
    free(c->instance);
    free(c);
    return NULL;
  }
  return c;
}

void fmi2FreeInstance(fmi2Component comp) {
  instance_t *c = comp;
  if (!c) return;
  if (c->h) davit_destroy(c->h);
  free(c->instance);
  free(c);
}

fmi2Status fmi2SetupExperiment(fmi2Component c, fmi2Boolean tol_defined, fmi2Real tol,
                               fmi2Real start, fmi2Boolean stop_defined, fmi2Real stop) {
  (void)c; (void)tol_defined; (void)tol; (void)stop_defined; (void)stop;
  return start == 0.0 ? fmi2OK : fmi2Error;  /* a launch starts at t = 0 */
}

fmi2Status fmi2EnterInitializationMode(fmi2Component comp) {
  instance_t *c = comp;
  if (c->h) return fmi2OK;
  if (davit_create_file(c->deck, &c->h) != DAVIT_OK) {
    fail(c, c->deck);  /* the failed handle carries the message; then it goes */
    davit_destroy(c->h);
    c->h = NULL;
    return fmi2Error;
  }
  return fmi2OK;
}

fmi2Status fmi2ExitInitializationMode(fmi2Component c) { (void)c; return fmi2OK; }
fmi2Status fmi2Terminate(fmi2Component c) { (void)c; return fmi2OK; }

fmi2Status fmi2Reset(fmi2Component comp) {
  instance_t *c = comp;
  if (c->h) davit_destroy(c->h);
  c->h = NULL;
  c->winch = c->winch_set = -1.0;
  c->release = c->released = 0;
  return fmi2EnterInitializationMode(comp);
}

static int outputs(instance_t *c, double v[7]) {
  double pose[12], sl[2], ev[4];
  if (davit_boat_pose(c->h, pose) != DAVIT_OK || davit_sling_tensions(c->h, sl) != DAVIT_OK ||
      davit_events(c->h, ev) != DAVIT_OK)
    return 0;
  v[0] = pose[0]; v[1] = pose[1]; v[2] = pose[2];
  v[3] = sl[0]; v[4] = sl[1];
  v[5] = ev[1]; v[6] = ev[2];
  return 1;
}

fmi2Status fmi2GetReal(fmi2Component comp, const fmi2ValueReference vr[], size_t n, fmi2Real value[]) {
  instance_t *c = comp;
  double v[7];
  if (!c->h || !outputs(c, v)) return fail(c, "outputs");
  for (size_t i = 0; i < n; i++) {
    if (vr[i] <= 6) value[i] = v[vr[i]];
    else if (vr[i] == 10) value[i] = c->winch_set;
    else return fmi2Error;
  }
  return fmi2OK;
}

fmi2Status fmi2SetReal(fmi2Component comp, const fmi2ValueReference vr[], size_t n, const fmi2Real value[]) {
  instance_t *c = comp;
  for (size_t i = 0; i < n; i++) {
    if (vr[i] != 10) return fmi2Error;
    c->winch_set = value[i];
  }
  return fmi2OK;
}

fmi2Status fmi2GetBoolean(fmi2Component comp, const fmi2ValueReference vr[], size_t n, fmi2Boolean value[]) {
  instance_t *c = comp;
  for (size_t i = 0; i < n; i++) {
    if (vr[i] != 11) return fmi2Error;
    value[i] = c->release;
  }
  return fmi2OK;
}

fmi2Status fmi2SetBoolean(fmi2Component comp, const fmi2ValueReference vr[], size_t n, const fmi2Boolean value[]) {
  instance_t *c = comp;
  for (size_t i = 0; i < n; i++) {
    if (vr[i] != 11) return fmi2Error;
    c->release = value[i] ? 1 : 0;
  }
  return fmi2OK;
}

fmi2Status fmi2GetInteger(fmi2Component c, const fmi2ValueReference vr[], size_t n, fmi2Integer v[]) {
  (void)c; (void)vr; (void)v;
  return n == 0 ? fmi2OK : fmi2Error;
}
fmi2Status fmi2SetInteger(fmi2Component c, const fmi2ValueReference vr[], size_t n, const fmi2Integer v[]) {
  (void)c; (void)vr; (void)v;
  return n == 0 ? fmi2OK : fmi2Error;
}
fmi2Status fmi2GetString(fmi2Component c, const fmi2ValueReference vr[], size_t n, fmi2String v[]) {
  (void)c; (void)vr; (void)v;
  return n == 0 ? fmi2OK : fmi2Error;
}
fmi2Status fmi2SetString(fmi2Component c, const fmi2ValueReference vr[], size_t n, const fmi2String v[]) {
  (void)c; (void)vr; (void)v;
  return n == 0 ? fmi2OK : fmi2Error;
}

/* the inputs act at the communication point, before the step */
fmi2Status fmi2DoStep(fmi2Component comp, fmi2Real t, fmi2Real h, fmi2Boolean no_set_prior) {
  instance_t *c = comp;
  (void)no_set_prior;
  if (!c->h) return fail(c, "fmi2DoStep");
  if (c->winch_set >= 0.0 && c->winch_set != c->winch) {
    if (davit_set_winch_speed(c->h, c->winch_set, 0.0) != DAVIT_OK) return fail(c, "winch speed");
    c->winch = c->winch_set;
  }
  if (c->release && !c->released) {
    if (davit_release(c->h) != DAVIT_OK) return fail(c, "release");
    c->released = 1;
  }
  if (davit_finished(c->h)) return fmi2OK;
  if (davit_advance_to(c->h, t + h) != DAVIT_OK) return fail(c, "advance");
  return fmi2OK;
}

fmi2Status fmi2CancelStep(fmi2Component c) { (void)c; return fmi2Error; }

fmi2Status fmi2GetStatus(fmi2Component c, const fmi2StatusKind k, fmi2Status *v) {
  (void)c; (void)k; (void)v;
  return fmi2Discard;
}
fmi2Status fmi2GetRealStatus(fmi2Component comp, const fmi2StatusKind k, fmi2Real *v) {
  instance_t *c = comp;
  if (k != fmi2LastSuccessfulTime || !c->h) return fmi2Discard;
  *v = davit_time(c->h);
  return fmi2OK;
}
fmi2Status fmi2GetIntegerStatus(fmi2Component c, const fmi2StatusKind k, fmi2Integer *v) {
  (void)c; (void)k; (void)v;
  return fmi2Discard;
}
fmi2Status fmi2GetBooleanStatus(fmi2Component comp, const fmi2StatusKind k, fmi2Boolean *v) {
  instance_t *c = comp;
  if (k != fmi2Terminated || !c->h) return fmi2Discard;
  *v = davit_finished(c->h) ? fmi2True : fmi2False;
  return fmi2OK;
}
fmi2Status fmi2GetStringStatus(fmi2Component c, const fmi2StatusKind k, fmi2String *v) {
  (void)c; (void)k; (void)v;
  return fmi2Discard;
}

/* The FMU state: the C ABI's snapshot (deck, controls, steps, state: restored by a replay
 * of the run, so a restore costs the replayed time) behind the inputs' bookkeeping. */
typedef struct {
  double winch, winch_set;
  int release, released;
  size_t n;
  uint8_t *bytes;
} fmu_state_t;

static void free_state(fmu_state_t *s) {
  if (!s) return;
  free(s->bytes);
  free(s);
}

fmi2Status fmi2GetFMUstate(fmi2Component comp, fmi2FMUstate *state) {
  instance_t *c = comp;
  if (!c->h) return fmi2Error;
  fmu_state_t *s = *state ? (fmu_state_t *)*state : calloc(1, sizeof *s);
  if (!s) return fmi2Error;
  size_t n = davit_save_size(c->h);
  uint8_t *b = realloc(s->bytes, n);
  if (!b) return fmi2Error;
  s->bytes = b;
  s->n = n;
  if (davit_save(c->h, s->bytes, n) != DAVIT_OK) return fail(c, "save");
  s->winch = c->winch;
  s->winch_set = c->winch_set;
  s->release = c->release;
  s->released = c->released;
  *state = s;
  return fmi2OK;
}

fmi2Status fmi2SetFMUstate(fmi2Component comp, fmi2FMUstate state) {
  instance_t *c = comp;
  fmu_state_t *s = state;
  if (!c->h || !s) return fmi2Error;
  if (davit_restore(c->h, s->bytes, s->n) != DAVIT_OK) return fail(c, "restore");
  c->winch = s->winch;
  c->winch_set = s->winch_set;
  c->release = s->release;
  c->released = s->released;
  return fmi2OK;
}

fmi2Status fmi2FreeFMUstate(fmi2Component c, fmi2FMUstate *state) {
  (void)c;
  if (state && *state) free_state(*state);
  if (state) *state = NULL;
  return fmi2OK;
}

/* serialized: the four bookkeeping fields, then the snapshot's bytes */
#define HEAD (2 * sizeof(double) + 2 * sizeof(int))

fmi2Status fmi2SerializedFMUstateSize(fmi2Component c, fmi2FMUstate state, size_t *n) {
  (void)c;
  fmu_state_t *s = state;
  if (!s) return fmi2Error;
  *n = HEAD + s->n;
  return fmi2OK;
}

fmi2Status fmi2SerializeFMUstate(fmi2Component c, fmi2FMUstate state, fmi2Byte b[], size_t n) {
  (void)c;
  fmu_state_t *s = state;
  if (!s || n < HEAD + s->n) return fmi2Error;
  memcpy(b, &s->winch, sizeof(double));
  memcpy(b + sizeof(double), &s->winch_set, sizeof(double));
  memcpy(b + 2 * sizeof(double), &s->release, sizeof(int));
  memcpy(b + 2 * sizeof(double) + sizeof(int), &s->released, sizeof(int));
  memcpy(b + HEAD, s->bytes, s->n);
  return fmi2OK;
}

fmi2Status fmi2DeSerializeFMUstate(fmi2Component c, const fmi2Byte b[], size_t n, fmi2FMUstate *state) {
  (void)c;
  if (n < HEAD) return fmi2Error;
  fmu_state_t *s = calloc(1, sizeof *s);
  if (!s) return fmi2Error;
  s->n = n - HEAD;
  s->bytes = malloc(s->n ? s->n : 1);
  if (!s->bytes) {
    free(s);
    return fmi2Error;
  }
  memcpy(&s->winch, b, sizeof(double));
  memcpy(&s->winch_set, b + sizeof(double), sizeof(double));
  memcpy(&s->release, b + 2 * sizeof(double), sizeof(int));
  memcpy(&s->released, b + 2 * sizeof(double) + sizeof(int), sizeof(int));
  memcpy(s->bytes, b + HEAD, s->n);
  *state = s;
  return fmi2OK;
}

/* not supported: directional derivatives, input and output derivatives */
fmi2Status fmi2GetDirectionalDerivative(fmi2Component c, const fmi2ValueReference u[], size_t nu,
                                        const fmi2ValueReference z[], size_t nz,
                                        const fmi2Real dv[], fmi2Real dz[]) {
  (void)c; (void)u; (void)nu; (void)z; (void)nz; (void)dv; (void)dz;
  return fmi2Error;
}
fmi2Status fmi2SetRealInputDerivatives(fmi2Component c, const fmi2ValueReference vr[], size_t n,
                                       const fmi2Integer o[], const fmi2Real v[]) {
  (void)c; (void)vr; (void)n; (void)o; (void)v;
  return fmi2Error;
}
fmi2Status fmi2GetRealOutputDerivatives(fmi2Component c, const fmi2ValueReference vr[], size_t n,
                                        const fmi2Integer o[], fmi2Real v[]) {
  (void)c; (void)vr; (void)n; (void)o; (void)v;
  return fmi2Error;
}
