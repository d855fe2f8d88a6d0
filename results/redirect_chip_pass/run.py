"""Writes results.json: chip-pass completions over a blocker (python results/redirect_chip_pass/run.py OUT.json)."""
import json, sys
from ssl_marl.skills.chip_pass import chip_pass_completion
out = {}
for name, kw, n in (("chip", dict(chip=True), 300), ("chip_realistic", dict(chip=True, realism="realistic"), 300), ("flat", dict(chip=False), 100)):
    out[name] = chip_pass_completion(n, seed=10_000, **kw)
    print(name, out[name], flush=True)
json.dump(out, open(sys.argv[1], "w"), indent=1)
