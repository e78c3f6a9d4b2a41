"""A scripted trainee on the default Level 5 launch, through the library (import davit):
lower at the deck's speed, stop for 5 s at 20 s, lower faster, let the boat become
waterborne and release by hand, then print what happened and the rule checks.

    bash make.sh demo                       # builds build/libdavit.so, makes davit importable
    python3 python/examples/trainee.py [DECK]
"""
import sys

import davit

deck = sys.argv[1] if len(sys.argv) > 1 else "input/iiib_level5_090.nml"
# the trainee opens the hooks, not the deck's automatic release once waterborne
with open(deck) as f:
    text = f.read().replace("&rigging", "&rigging\n  release = .false.", 1)
with davit.Launch.from_text(text, deck) as run:
    run.advance_to(20.0)
    print(f"t = {run.time:5.2f} s  boat z = {run.boat_pose()['position'][2]:6.2f} m  "
          f"slings {run.sling_tensions() / 1e3} kN: braking")
    run.brake(0.5)
    run.advance_to(25.0)
    snapshot = run.save()                 # a point to come back to
    print(f"t = {run.time:5.2f} s  saved {len(snapshot)} bytes; lowering at 1.0 m/s (drum)")
    run.set_winch_speed(1.0, ramp=1.0)
    while not run.finished:
        run.advance(0.1)
        events = run.events()
        if events["waterborne"] is not None and events["release"] is None:
            run.release()
            print(f"t = {run.time:5.2f} s  waterborne since {events['waterborne']:.2f} s: "
                  "hooks released")
    events = run.events()
    print(f"end t = {run.time:.2f} s; first contact {events['first_contact']}, "
          f"{len(events['impacts'])} impacts")
    for name, (value, limit, margin) in run.rule_checks().items():
        print(f"  {name:15s} {value:12.4g}  limit {limit:10.4g}  margin {margin:6.2f}")
