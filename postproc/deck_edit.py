"""Editing davit decks as text and running them: a key set in its group (replaced or
added), a study's run spec ('integrator key=value ...') turned into a deck, a deck text run
with `davit run`. Used by the studies, the bench reference and the tests."""
import os
import re
import subprocess

KEY_GROUPS = {"dt": "simulation", "dt_contact": "simulation", "rtol": "simulation",
              "atol": "simulation", "wave_update": "simulation", "integrator": "simulation",
              "t_end": "simulation", "output_interval": "simulation",
              "fixed_step": "simulation",
              "lumps": "rigging", "sheaves": "rigging", "strips": "boat",
              "frozen": "ship", "n_frequencies": "sea", "n_directions": "sea",
              "wave_type": "sea", "seed": "simulation", "water_model": "boat",
              "blocks": "rigging", "contact_approach": "simulation",
              "summation": "sea", "substeps": "simulation", "kinematics": "sea"}
STRING_KEYS = {"sheaves", "integrator", "wave_type", "water_model", "blocks",
               "contact_approach", "summation", "kinematics"}


def override(deck, group, key, value):
    """The deck text with `key = value` set in `&group` (replaced or added)."""
    literal = f"'{value}'" if key in STRING_KEYS else str(value)
    # the group where it opens a line: a comment that names "&group" is not the group
    pattern = re.compile(rf"(^[ \t]*&{group}\b.*?)(\n\s*/)", re.S | re.M)
    match = pattern.search(deck)
    if not match:
        return deck.rstrip() + f"\n&{group}\n  {key} = {literal}\n/\n"
    block = match.group(1)
    line = re.compile(rf"^(\s*){key}\s*=.*$", re.M)
    if line.search(block):
        block = line.sub(rf"\g<1>{key} = {literal}", block, count=1)
    else:
        block = block + f"\n  {key} = {literal}"
    return deck[:match.start()] + block + match.group(2) + deck[match.end():]


def variant(base_text, spec, t_end):
    """Deck text of one run spec 'integrator key=value ...'."""
    words = spec.split()
    deck = override(base_text, "simulation", "integrator", words[0])
    deck = override(deck, "simulation", "t_end", t_end)
    for word in words[1:]:
        key, value = word.split("=")
        if key not in KEY_GROUPS:
            raise ValueError(f"study run '{spec}': unknown key '{key}'")
        deck = override(deck, KEY_GROUPS[key], key, value)
    return deck


def run_davit(davit, deck_text, workdir, name):
    """Run one variant; returns the output path and whether it completed."""
    deck = os.path.join(workdir, name + ".nml")
    out = os.path.join(workdir, name + ".h5")
    with open(deck, "w") as f:
        f.write(deck_text)
    result = subprocess.run([davit, "run", deck, "-o", out], capture_output=True, text=True)
    return out, result.returncode == 0, result.stderr.strip()
