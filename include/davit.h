/* davit as a library: the C ABI of build/libdavit.so (bash make.sh demo or setup builds it).
 *
 * A handle is one launch run step by step (src/capi/): created from a deck file or deck
 * text, advanced in time, controlled (winch, brake, hooks, ship's heading), read (poses,
 * tensions, fender forces, events, rule checks) and saved to / restored from bytes.
 * Handles share nothing: each thread may own one. Every call that can fail returns a code
 * (DAVIT_OK = 0) and keeps the code and a message in its handle until the next call on it;
 * davit_error_message reads the message (a deck's names its file, line, group and key).
 * Units: SI; frames as in davit's output files (inertial frame N: x, y horizontal, z down).
 * Guide: doc/howto/library.md.
 */
#ifndef DAVIT_H
#define DAVIT_H

#include <stddef.h>
#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

typedef struct davit_session *davit_handle;

enum davit_code {
  DAVIT_OK = 0,
  DAVIT_E_INPUT = 1,    /* the deck: unreadable, invalid, or a scene without a boat */
  DAVIT_E_RUN = 2,      /* the run diverged or a step failed (state kept at the last good step) */
  DAVIT_E_ARG = 3,      /* a bad argument: null handle, short buffer, control out of range */
  DAVIT_E_SNAPSHOT = 4  /* davit_restore: corrupt bytes, or a replay that differs */
};

/* Create a handle in *out from a deck file, or from deck text (name: for messages only).
 * *out is set even on failure (it carries the code and message): destroy it either way.
 * Data files the deck names are searched as davit run does (DAVIT_PATH). */
int davit_create_file(const char *path, davit_handle *out);
int davit_create_text(const char *name, const char *text, davit_handle *out);
void davit_destroy(davit_handle h);

int davit_error_code(davit_handle h);
/* Copies the message, NUL-terminated and cut to len - 1 bytes; returns its full length. */
size_t davit_error_message(davit_handle h, char *buf, size_t len);

/* Step to time t (or by dt): whole steps of davit run's own sequence, so the time reached
 * is the first step end >= t (exact when t is a multiple of the deck's output interval
 * and of dt). Stops early at the run's end (davit_finished). */
int davit_advance_to(davit_handle h, double t);
int davit_advance(davit_handle h, double dt);
double davit_time(davit_handle h);
int davit_finished(davit_handle h);

/* Controls, applied at the current time, before the next step. */
int davit_set_winch_speed(davit_handle h, double drum_speed, double ramp); /* m/s in [-10, 10] (pay-out > 0), reached over ramp s */
int davit_brake(davit_handle h, double time_to_rest);                      /* the drum to rest over time_to_rest s */
int davit_release(davit_handle h);                                         /* open the hooks now */
int davit_set_heading(davit_handle h, double heading);                     /* rad; a moving ship that keeps its heading */

/* Getters. sizes: state components, fall segments, fenders, rule checks. */
int davit_sizes(davit_handle h, int sizes[4]);
int davit_state(davit_handle h, double *y, int len);
/* boat: CG position (3), Euler angles (3), CG velocity (3), angular velocity, boat axes (3) */
int davit_boat_pose(davit_handle h, double out[12]);
/* ship: CG position (3), Euler angles (3) */
int davit_ship_pose(davit_handle h, double out[6]);
int davit_blocks(davit_handle h, double out[6]);         /* 2 movable blocks, x y z each */
int davit_hooks(davit_handle h, double out[6]);          /* 2 hooks, x y z each */
int davit_sling_tensions(davit_handle h, double out[2]); /* N, at the hooks (/slings/tension) */
int davit_fall_tensions(davit_handle h, double *out, int len);  /* N, each cable segment */
int davit_fender_forces(davit_handle h, double *out, int len);  /* N, each fender */
/* times of first contact, waterborne, release (-1: not yet) and the number of impacts */
int davit_events(davit_handle h, double out[4]);
/* 4 a impact: onset s, fender (1-based), impact speed m/s, peak force N */
int davit_impacts(davit_handle h, double *out, int len);
/* the rule checks so far: value, limit, margin each (NaN: not applicable yet) */
int davit_rule_checks(davit_handle h, double *value, double *limit, double *margin, int len);
int davit_check_name(int i, char *buf, size_t len); /* 1-based; returns its length, -1 if none */

/* The whole run's state as bytes (the deck, the controls so far, the step count and a
 * check); davit_restore rebuilds a handle's run from them by replay and refuses one that
 * differs in any bit from the check. */
size_t davit_save_size(davit_handle h);
int davit_save(davit_handle h, uint8_t *buf, size_t len);
int davit_restore(davit_handle h, const uint8_t *buf, size_t len);

#ifdef __cplusplus
}
#endif

#endif /* DAVIT_H */
