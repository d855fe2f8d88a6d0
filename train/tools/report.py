"""Every table of docs/RESULTS.md, generated from the result records under ``results/``.

    python -m train.report [--results results] [--doc docs/RESULTS.md] [--check] [--print NAME]

Each table sits in the doc between ``<!-- table:NAME -->`` and ``<!-- /table:NAME -->``;
this rewrites what lies between every pair of markers from :data:`TABLES` (the row
builders are in :mod:`train.tools.report_tables` and
:mod:`train.tools.report_match_tables`). ``--check`` changes nothing and exits 1
naming the tables whose text differs from what the records give (and any marker
without a table, or table without a marker). A result goes into the doc by adding its
record under ``results/`` and its name to the table's entry here.
"""

from __future__ import annotations

import argparse
import re
import sys
from pathlib import Path
from typing import Callable

from ssl_marl.io import atomic_write_bytes
from train.tools import report_match_tables as m
from train.tools import report_tables as t

SKILLS_PAPER = ["go_to_ball_baseline", "go_to_ball_baseline_realistic", "go_to_ball_learned",
                "go_to_ball_learned_realistic", "aim_to_shoot_baseline", "aim_to_shoot_baseline_realistic",
                "aim_to_shoot_learned", "aim_to_shoot_learned_realistic"]
SKILLS_TRACKER = ["go_to_ball_baseline_div_a", "go_to_ball_learned_div_a", "go_to_ball_learned_realistic_tracker",
                  "go_to_ball_learned_realistic_tracker_div_a", "aim_to_shoot_learned_realistic_tracker"]
SKILLS_RANDOMIZED = ["go_to_ball_baseline_randomized_tracker", "go_to_ball_learned_randomized_tracker",
                     "go_to_ball_learned_randomized_tracker_div_a", "aim_to_shoot_baseline_randomized_tracker",
                     "aim_to_shoot_learned_randomized_tracker"]
PASSING_SKILLS = ["pass_baseline", "pass_baseline_realistic", "pass_learned", "pass_learned_realistic",
                  "receive_baseline", "receive_baseline_realistic", "receive_baseline_realistic_tracker",
                  "receive_learned", "receive_learned_realistic", "receive_baseline_div_a", "receive_learned_div_a"]
REDIRECT_SKILLS = ["redirect_baseline", "redirect_baseline_realistic", "redirect_learned", "redirect_learned_realistic"]
CHIP_PASS_SKILLS = ["chip_pass_baseline", "chip_pass_baseline_realistic", "chip_pass_learned",
                    "chip_pass_learned_realistic"]
PASS_ENDURANCE = ["pass_endurance_baseline", "pass_endurance_baseline_realistic", "pass_endurance_learned_pass",
                  "pass_endurance_learned_pass_realistic"]
TACTIC = ["tactic_baseline", "tactic_baseline_realistic", "tactic_learned", "tactic_learned_realistic"]
DRIBBLE = [f"tactic_dribble_{s}_{r}_{f}" for s in ("baseline", "learned") for r in ("none", "realistic")
           for f in ("div_b", "div_a")]
ROLLING_ACTOR = {"runs/gtb_rolling_s0/actors/actor-000740001.pt": "ball velocity (`go_to_ball/v2`, shipped)"}
TRACKER_PAIRS = [("go-to-ball, baseline", "go_to_ball_baseline", "go_to_ball_baseline"),
                 ("aim-to-shoot, baseline", "aim_to_shoot_baseline", "aim_to_shoot_baseline"),
                 ("aim-to-shoot, learned", "aim_to_shoot_learned", "aim_to_shoot_learned"),
                 ("go-to-ball-and-shoot, baseline skills", "tactic_baseline", "tactic_baseline")]
PASSING_SERIES = ["match_passing_learned_vs_baseline_snap", "match_passing_learned_vs_passing_learned_snap",
                  "match_passing_learned_vs_passing_baseline_snap"]
SERIES_600_SSL = ["match_passing_learned_vs_baseline_600_plain", "match_passing_learned_vs_baseline_600_ssl"]
ATTACK_SERIES = ["match_attack_learned_vs_baseline_600", "match_attack_learned_vs_passing_learned_600",
                 "match_attack_learned_selfplay_600", "match_attack_learned_vs_baseline_600_realistic",
                 "match_attack_learned_vs_baseline_600_div_a_11v11", "match_attack_learned_vs_attack_baseline_600",
                 "match_attack_learned_vs_attack_baseline_600_79000",
                 "match_attack_learned_vs_attack_baseline_600_realistic",
                 "match_attack_learned_vs_attack_baseline_600_div_a_11v11"]
#: the attacking-game issue's target series played again with the current code (seeds 83000-87009)
ATTACK_TARGETS = ["match_attack_learned_vs_baseline_600_83000", "match_attack_learned_vs_passing_learned_600_84000",
                  "match_attack_learned_selfplay_600_85000", "match_attack_learned_vs_baseline_600_realistic_86000",
                  "match_attack_learned_vs_baseline_600_div_a_11v11_87000"]
#: four of the five target series with the plays kicking chips and redirects through the skills (seeds 90000-90319)
ATTACK_TARGETS_SKILLS = ["match_attack_learned_vs_baseline_600_90000",
                         "match_attack_learned_vs_passing_learned_600_90100",
                         "match_attack_learned_selfplay_600_90200",
                         "match_attack_learned_vs_baseline_600_realistic_90300"]
#: the target series with colour-fair physics (commit d55290a), the attacking team half its matches blue, half yellow
ATTACK_TARGETS_FAIR = ["match_attack_learned_vs_baseline_600_94000", "match_baseline_vs_attack_learned_600_94010",
                       "match_attack_learned_vs_passing_learned_600_94100", "match_passing_learned_vs_attack_learned_600_94110",
                       "match_attack_learned_selfplay_600_94200",
                       "match_attack_learned_vs_baseline_600_realistic_94300",
                       "match_baseline_vs_attack_learned_600_realistic_94305",
                       "match_attack_learned_vs_baseline_600_div_a_11v11_94400",
                       "match_baseline_vs_attack_learned_600_div_a_11v11_94405"]
#: the same from the attacking team's side, both colours pooled
ATTACK_TARGETS_FAIR_POOLED = [
    ("attack-learned (vs baseline)", (("match_attack_learned_vs_baseline_600_94000", "blue"),
                                      ("match_baseline_vs_attack_learned_600_94010", "yellow"))),
    ("attack-learned (vs passing-learned)", (("match_attack_learned_vs_passing_learned_600_94100", "blue"),
                                             ("match_passing_learned_vs_attack_learned_600_94110", "yellow"))),
    ("attack-learned (self-play, blue's side)", (("match_attack_learned_selfplay_600_94200", "blue"),)),
    ("attack-learned (vs baseline, realistic)", (("match_attack_learned_vs_baseline_600_realistic_94300", "blue"),
                                                 ("match_baseline_vs_attack_learned_600_realistic_94305", "yellow"))),
    ("attack-learned (vs baseline, 11v11 Division A)",
     (("match_attack_learned_vs_baseline_600_div_a_11v11_94400", "blue"),
      ("match_baseline_vs_attack_learned_600_div_a_11v11_94405", "yellow")))]
#: the targets again with the pressed passer (commit fcb21d2, seeds 95000-95409)
ATTACK_TARGETS_PRESS = [n.replace("_94", "_95") for n in ATTACK_TARGETS_FAIR]
ATTACK_TARGETS_PRESS_POOLED = [(label, tuple((n.replace("_94", "_95"), side) for n, side in parts))
                               for label, parts in ATTACK_TARGETS_FAIR_POOLED]
#: the targets again with the pressed receive retrained under its gate (commit 845ac88, seeds 99300-99379)
_SEEDS_99 = {"_94000": "_99300", "_94010": "_99310", "_94100": "_99320", "_94110": "_99330", "_94200": "_99340",
             "_94300": "_99360", "_94305": "_99365", "_94400": "_99370", "_94405": "_99375"}


def _seeds_99(name: str) -> str:
    return name[:-6] + _SEEDS_99[name[-6:]]


ATTACK_TARGETS_99 = [_seeds_99(n) for n in ATTACK_TARGETS_FAIR]
ATTACK_TARGETS_99_POOLED = [(label, tuple((_seeds_99(n), side) for n, side in parts))
                            for label, parts in ATTACK_TARGETS_FAIR_POOLED]
#: the targets in SSL format with SSL free-kick spots and the set-piece shot (commit 9e6784a, seeds 104600-105009)
ATTACK_TARGETS_SSL_104600 = ["match_attack_learned_vs_baseline_600_ssl_104600",
                             "match_attack_learned_vs_passing_learned_600_ssl_104700",
                             "match_attack_learned_selfplay_600_ssl_104800",
                             "match_attack_learned_vs_baseline_600_ssl_realistic_104900",
                             "match_attack_learned_vs_baseline_600_ssl_div_a_11v11_105000"]
#: the attacking team's realistic target series again with the code of commit 2c63231 (spent pass setups, dribble limit)
ATTACK_REALISTIC_SSL_105500 = ["match_attack_learned_vs_baseline_600_ssl_realistic_104900",
                               "match_attack_learned_vs_baseline_600_ssl_realistic_105500"]
#: the attacking team's target series in the SSL format with its clock stopped during STOP (commit 1772b71)
ATTACK_TARGETS_SSL_105600 = ["match_attack_learned_vs_baseline_600_ssl_105600",
                             "match_attack_learned_vs_passing_learned_600_ssl_105700",
                             "match_attack_learned_selfplay_600_ssl_105800",
                             "match_attack_learned_vs_baseline_600_ssl_realistic_106000",
                             "match_attack_learned_vs_baseline_600_ssl_div_a_11v11_105900"]
ATTACK_SSL_106200 = ["match_attack_learned_vs_baseline_600_ssl_106200",
                     "match_attack_learned_vs_passing_learned_600_ssl_106300",
                     "match_attack_learned_vs_baseline_600_ssl_realistic_106400",
                     "match_attack_learned_vs_baseline_600_ssl_106700",
                     "match_attack_learned_vs_baseline_600_ssl_realistic_106800",
                     "match_attack_learned_selfplay_600_ssl_106500",
                     "match_attack_learned_vs_baseline_600_ssl_div_a_11v11_106600"]
ATTACK_SSL_106200_POOLED = [("attack-learned vs baseline, the attacker that waits outside the defense area",
                             (("match_attack_learned_vs_baseline_600_ssl_106200", "blue"),
                              ("match_attack_learned_vs_baseline_600_ssl_106700", "blue"))),
                            ("the same under `--realism realistic`",
                             (("match_attack_learned_vs_baseline_600_ssl_realistic_106400", "blue"),
                              ("match_attack_learned_vs_baseline_600_ssl_realistic_106800", "blue")))]
ATTACK_SSL_106200_FOULS = [("the attacker goes into the defense area", "match_attack_learned_vs_baseline_600_ssl_105600"),
                           ("the attacker waits outside it", "match_attack_learned_vs_baseline_600_ssl_106200"),
                           ("the attacker goes into the defense area",
                            "match_attack_learned_vs_passing_learned_600_ssl_105700"),
                           ("the attacker waits outside it", "match_attack_learned_vs_passing_learned_600_ssl_106300")]
#: self-play series of one team, pooled: blue's surplus over yellow (a colour bias shows here)
COLOUR_BALANCE = [("attacking team, the robot order decides a contested ball",
                   ("match_attack_learned_selfplay_600", "match_attack_learned_selfplay_600_85000",
                    "match_attack_learned_selfplay_600_90200")),
                  ("attacking team, the ball's place on the face decides (fixed)", ("match_attack_learned_selfplay_600_92000",)),
                  ("attacking team, as above and Box2D bodies created in an order drawn from the scene",
                   ("match_attack_learned_selfplay_600_94200",)),
                  ("attacking team, the two rows above pooled",
                   ("match_attack_learned_selfplay_600_92000", "match_attack_learned_selfplay_600_94200")),
                  ("passing team (no kick on contact)", ("match_passing_learned_vs_passing_learned_snap",))]
ATTACK_SKILL_SWAPS = ["match_attack_learned_vs_attack_baseline_600", "tuning/swap_none_all_learned",
                      "tuning/swap_aim_to_shoot_baseline",
                      "tuning/swap_pass_receive_baseline", "tuning/swap_go_to_ball_baseline",
                      "tuning/swap_go_to_ball_rolling"]
#: the same swaps with the code of the pressed passer (commit e8e1dc0), new seeds 98200-98219
ATTACK_SKILL_SWAPS_98 = ["tuning/swap98_none_all_learned", "tuning/swap98_go_to_ball_baseline",
                         "tuning/swap98_pass_receive_baseline", "tuning/swap98_pass_baseline",
                         "tuning/swap98_receive_baseline"]
#: self-play ``benchmarks/match_variants.py`` runs of the set pieces' pass threshold (both teams' statistics)
SET_PIECE_VARIANTS_SELFPLAY = [
    ("control (`ssl`)", "selfplay_ssl_61850_both.json"), ("control (`ssl`)", "selfplay_ssl_61854_both.json"),
    ("set pieces pass only from success 0.6 (`ssl-restart-pass-0.6`)", "selfplay_ssl-restart-pass-0.6_61850.json"),
    ("set pieces pass only from success 0.7 (`ssl-restart-pass-0.7`)", "selfplay_ssl-restart-pass-0.7_61850.json"),
    ("set pieces pass only from success 0.7 (`ssl-restart-pass-0.7`)", "selfplay_ssl-restart-pass-0.7_61854.json")]
#: self-play tuning of the set pieces' receivable chip (``ssl-restart-chip-3``) beside the control, seeds 61880-61883
SET_PIECE_CHIP_SELFPLAY = [
    ("control (`ssl`)", tuple(f"selfplay_ssl_{s}_both.json" for s in range(61880, 61884))),
    ("set-piece chips the receiver can take, arriving at most 3 m/s (`ssl-restart-chip-3`)",
     tuple(f"selfplay_ssl-restart-chip-3_{s}.json" for s in range(61880, 61884))),
    ("set pieces pass only from success 0.7 (`ssl-restart-pass-0.7`)",
     tuple(f"selfplay_ssl-restart-pass-0.7_{s}.json" for s in range(61880, 61884)))]
#: the second defender only against a threat (``ssl-defender-1-opp-2``) beside the control, against the no-pass
#: baseline, seeds 61884-61889
MATCH_VARIANTS_DEFENDER_1 = [
    ("SSL format, the second defender always on (`ssl`, the code before)",
     tuple(f"baseline_ssl_{s}.json" for s in range(61884, 61890))),
    ("the second defender only with two opponents in our half or the ball there (`ssl-defender-1-opp-2`)",
     tuple(f"baseline_ssl-defender-1-opp-2_{s}.json" for s in range(61884, 61890)))]
#: ``benchmarks/match_variants.py`` runs (label, file under results/tuning/match_variants/)
MATCH_VARIANTS = [("plain format (play restarts at once)", "plain.json"),
                  ("free kicks, no STOP", "free-kick.json"),
                  ("free kicks after a 1 s STOP", "free-kick-stop.json"),
                  ("free kicks after a 1 s STOP, fouls called", "free-kick-stop-fouls.json"),
                  ("plain, the carrier keeps up to 2 s (`max_keep_s`)", "keep-2s.json"),
                  ("plain, an expired keep never shoots", "keep-inf.json"),
                  ("plain, an expired keep passes (`keep_expiry=\"pass\"`)", "keep-pass.json"),
                  ("plain format, 10 more seeds", "seeds61510/plain.json"),
                  ("free kicks after a 1 s STOP, 10 more seeds", "seeds61510/free-kick-stop.json"),
                  ("plain, passes rated with a 1 m receiver guard (`receiver_guard_m`)", "receiver-guard.json"),
                  ("the same, 10 more seeds", "seeds61510/receiver-guard.json"),
                  ("self-play, plain format", ("selfplay/plain-61530.json", "selfplay/plain-61535.json")),
                  ("self-play, both teams with the 1 m receiver guard",
                   ("selfplay/receiver-guard-61530.json", "selfplay/receiver-guard-61535.json")),
                  ("self-play, SSL format", ("selfplay/ssl-61540.json", "selfplay/ssl-61545.json")),
                  ("self-play, SSL format, both teams with the 1 m receiver guard",
                   ("selfplay/ssl-receiver-guard-61540.json", "selfplay/ssl-receiver-guard-61545.json")),
                  ("plain, passes into a redirect kicked and rated to arrive at 4.5 m/s (`redirect_arrive_speed`)",
                   ("redirect-4.5.json", "seeds61510/redirect-4.5.json")),
                  ("plain, the plays kick chips and redirects through the skills (merged as 81b7d5a)",
                   ("playskills/plain-61500.json", "playskills/plain-61510.json")),
                  ("plain, colour-fair physics (d55290a), passes counted up to 4 m/s arrival",
                   ("press/plain-61500.json", "press/plain-61510.json")),
                  ("the same, a pressed passer kicks at once (`press_urgent_m` 0.6, `contested_kick`)",
                   ("press/press-0.6-61500.json", "press/press-0.6-61510.json"))]
#: the same matches against a weakened baseline defence and with the supports' edge spots
#: (``benchmarks/match_variants.py``; the first row's files are the pressed-passer rows above)
MATCH_VARIANTS_SELFPLAY_PASS = [("self-play, plain format", "selfplay_pass/plain-61700.json"),
                                ("both teams consider only passes rated >= 0.5 (`pass-0.5`)",
                                 "selfplay_pass/pass-0.5-61700.json"),
                                ("both teams consider only passes rated >= 0.65 (`pass-0.65`)",
                                 "selfplay_pass/pass-0.65-61700.json"),
                                ("both teams with the 1 m receiver guard (`receiver-guard`)",
                                 "selfplay_pass/receiver-guard-61700.json")]
MATCH_VARIANTS_SELFPLAY_ARRIVE = [("self-play, SSL format, the attacking team as it plays (flat passes arrive at 2 m/s)",
                                   "arrive/ssl-selfplay-61810.json"),
                                  ("both teams' flat passes kicked, and rated, to arrive at 3 m/s (`ssl-arrive-3`)",
                                   "arrive/ssl-arrive-3-selfplay-61810.json")]
#: shots aimed, and decided, by the shot lines' reach times (``benchmarks/match_variants.py``, this code's plain row)
MATCH_VARIANTS_SHOTS = [("the attacking team as it plays (plain format)", "shots/plain-61500.json"),
                        ("shots aimed at the line the defence reaches last (`aim-reach`)", "shots/aim-reach-61500.json"),
                        ("the decision also shoots when a line's margin is >= 0.05 s within 3.5 m (`reach-shot`; stopped "
                         "after 6 matches)", "shots/reach-shot-61500.json")]
#: 11v11 Division A: passes up to 8 m (``benchmarks/match_variants.py --robots 11 --field div_a``)
MATCH_VARIANTS_DIV_A = [("11v11 Division A, the attacking team as it plays (passes up to 6 m)", "div_a/plain-62010.json"),
                        ("11v11 Division A, passes up to 8 m (`pass-8m`)", "div_a/pass-8m-62010.json")]
#: 11v11 Division A: the carrier's keep rule, and the learned decision (same tuning seeds as ``MATCH_VARIANTS_DIV_A``)
MATCH_VARIANTS_DIV_A_KEEP = [
    ("11v11 Division A, the attacking team as it plays (as above)", "div_a/plain-62010.json"),
    ("the carrier keeps up to 2 s (`keep-2s`)", "div_a/keep-2s-62010.json"),
    ("an expired keep passes (`keep-pass`)", "div_a/keep-pass-62010.json"),
    ("an expired keep shoots only within 6 m of the goal (`keep-near-6`; stopped after 4 matches)",
     "div_a/keep-near-6-62010.json"),
    ("the carrier's open-play decision by the shipped attack-drill actor (`--blue attack-learned-decision`)",
     "div_a/learned-decision-62010.json")]
#: 11v11 Division A, SSL format: the learned-decision team with and without the keep tap
MATCH_VARIANTS_DIV_A_TAP = [
    ("SSL format, the learned-decision team as it plays", "div_a/ssl-learned-decision-62010.json"),
    ("SSL format, the keeping attacker taps the ball ahead at 0.7 m (`ssl-tap-0.7`)",
     "div_a/ssl-tap-0.7-learned-decision-62010.json")]
MATCH_VARIANTS_DIV_A_LONG_SHOT = [
    ("SSL format, the learned-decision team as it plays", "div_a/ssl-learned-decision-62104.json"),
    ("SSL format, no learned shot from farther than 6 m while another option is legal (`ssl-long-shot-6`)",
     "div_a/ssl-long-shot-6-learned-decision-62104.json"),
    ("6v6 Division B, no learned shot from farther than 6 m (`ssl-long-shot-6`)",
     "ssl-long-shot-6-learned-decision-62110.json")]
MATCH_VARIANTS_DEFENCE = [("the attacking team as it plays (pressed passer; seeds 61500-61509 as above)",
                           "press/press-0.6-61500.json"),
                          ("the opponent's plays keep one defender on the ball-goal line (`opp-one-defender`)",
                           "defence/opp-one-defender.json"),
                          ("the opponent's plays keep no defender (`opp-no-defender`)", "defence/opp-no-defender.json"),
                          ("the attacking team's supports also rate spots on the defence area's border (`edge-spots`)",
                           ("defence/edge-spots-61500.json", "defence/edge-spots-61510.json")),
                          ("the attacking team as it plays, the same 20 seeds",
                           ("press/press-0.6-61500.json", "press/press-0.6-61510.json"))]
MATCH_VARIANTS_SSL_MARKS = [("the attacking team as it plays (SSL format)", "marks/ssl-passing-61770.json"),
                            ("its marks turned a quarter towards the ball (`ssl-mark-0.25`)",
                             "marks/ssl-mark-0.25-passing-61770.json")]
MATCH_VARIANTS_SSL_OPP_AREA = [("the attacking team as it plays (SSL format)", "opp_area/ssl-baseline-61790.json"),
                               ("its attacker waits outside the opponent's defense area (`ssl-opp-area`)",
                                "opp_area/ssl-opp-area-baseline-61790.json")]
MATCH_VARIANTS_SSL_SCORING = [("the attacking team as it plays (the `ssl-opp-area` row above)",
                               "opp_area/ssl-opp-area-baseline-61790.json"),
                              ("open-play shot threshold 0.15 (`ssl-shoot-0.15`)",
                               "scoring/ssl-shoot-0.15-baseline-61790.json"),
                              ("supports' spots nearer the goal, `w_goal` 0.5 (`ssl-spots-goal-0.5`)",
                               "scoring/ssl-spots-goal-0.5-baseline-61790.json")]
FOUL_PROBES = [("the attacker goes for the ball in the opponent's defense area", "attack_vs_baseline.json"),
               ("waiting outside it (`--passing keep_out_of_opp_area=true`)", "attack_opp_area_vs_baseline.json")]
SET_PIECE_SERIES = ["match_attack_learned_vs_baseline_600_ssl_058d181", "match_attack_learned_vs_baseline_600_ssl",
                    "match_attack_learned_vs_baseline_600_ssl_20261127"]
SSL_FOULS_104100 = [("before the defender call and the braking fix", "match_attack_learned_vs_baseline_600_ssl_104100_8b7f0e3"),
                    ("with them", "match_attack_learned_vs_baseline_600_ssl_104100")]
SSL_SET_PIECES_104100 = [("set pieces carried off, a kicker's second touch after letting go called",
                          "match_attack_learned_vs_baseline_600_ssl_104100"),
                         ("set pieces kicked, a kicker still in contact called too",
                          "match_attack_learned_vs_baseline_600_ssl_104100_7e3a165"),
                         ("and a wall against the other side's set pieces",
                          "match_attack_learned_vs_baseline_600_ssl_104100_46fa628")]
KEEPAWAY = [("random", "keepaway_random"), ("always-hold", "keepaway_always-hold"),
            ("hand-coded", "keepaway_handcoded"), ("learned (shipped `keepaway.pt`, MAPPO seed 1)", "keepaway_learned")]
ATTACK = [("hand-coded (cost decision, shot threshold 0.25)", "attack_3v2_handcoded_snap"),
          ("learned, the previous actor (trained without the snap shot)", "attack_3v2_learned_snap"),
          ("learned (shipped `attack_3v2.pt`: retrained with the snap shot, `mappo_attack_snap_bc_s0`)",
           "attack_3v2_learned_snap_retrained")]
DECISION_SERIES = ["match_attack_learned_decision_vs_attack_learned_600",
                   "match_attack_learned_decision_vs_attack_learned_600_realistic",
                   "match_attack_learned_decision_vs_attack_learned_600_div_a_11v11",
                   "match_attack_learned_decision_vs_passing_learned_600"]
#: the learned decision against the hand-coded one with the contested-kick fix (seeds 93000-93029)
DECISION_SERIES_FAIR = ["match_attack_learned_decision_vs_attack_learned_600_93000",
                        "match_attack_learned_vs_attack_learned_decision_600_93030"]
#: the same 60 matches from the learned decision's side (blue in the first 30, yellow in the last 30)
DECISION_FAIR_POOLED = [("attack-learned, learned decision vs attack-learned",
                         (("match_attack_learned_decision_vs_attack_learned_600_93000", "blue"),
                          ("match_attack_learned_vs_attack_learned_decision_600_93030", "yellow"))),
                        ("the same with Box2D's body order fixed (commit d55290a)",
                         (("match_attack_learned_decision_vs_attack_learned_600_94500", "blue"),
                          ("match_attack_learned_vs_attack_learned_decision_600_94530", "yellow"))),
                        ("the same, `--realism realistic`",
                         (("match_attack_learned_decision_vs_attack_learned_600_realistic_94600", "blue"),
                          ("match_attack_learned_vs_attack_learned_decision_600_realistic_94610", "yellow"))),
                        ("the same, 11v11 Division A",
                         (("match_attack_learned_decision_vs_attack_learned_600_div_a_11v11_94700", "blue"),
                          ("match_attack_learned_vs_attack_learned_decision_600_div_a_11v11_94705", "yellow")))]
#: the learned decision against the hand-coded one with Box2D's body order fixed too (seeds 94500-94559)
DECISION_SERIES_FAIR2 = ["match_attack_learned_decision_vs_attack_learned_600_94500",
                         "match_attack_learned_vs_attack_learned_decision_600_94530",
                         "match_attack_learned_decision_vs_attack_learned_600_realistic_94600",
                         "match_attack_learned_vs_attack_learned_decision_600_realistic_94610",
                         "match_attack_learned_decision_vs_attack_learned_600_div_a_11v11_94700",
                         "match_attack_learned_vs_attack_learned_decision_600_div_a_11v11_94705"]
#: the learned decision against the hand-coded one with the pressed passer (commit fcb21d2, seeds 95500-95559)
DECISION_SERIES_PRESS = ["match_attack_learned_decision_vs_attack_learned_600_95500",
                         "match_attack_learned_vs_attack_learned_decision_600_95530",
                         "match_attack_learned_decision_vs_attack_learned_600_realistic_95600",
                         "match_attack_learned_vs_attack_learned_decision_600_realistic_95610"]
#: each pair of DECISION_SERIES_PRESS (learned decision blue, then yellow) from the learned side
DECISION_PRESS_POOLED = [m.both_colours(label, blue, yellow) for label, blue, yellow in zip(
    ("attack-learned, learned decision vs attack-learned (pressed passer, commit fcb21d2)",
     "the same, `--realism realistic`"), DECISION_SERIES_PRESS[::2], DECISION_SERIES_PRESS[1::2])]
#: the learned decision against the hand-coded one with the receive retrained under its gate (commit 845ac88)
DECISION_SERIES_99 = ["match_attack_learned_decision_vs_attack_learned_600_99400",
                      "match_attack_learned_vs_attack_learned_decision_600_99430"]
DECISION_99_POOLED = [m.both_colours("attack-learned, learned decision vs attack-learned (commit 845ac88)",
                                     DECISION_SERIES_99[0], DECISION_SERIES_99[1])]
#: the learned decision against the cost decision with the restart placement of commit 6c366aa (seeds 104000-104019, 104030-104049)
DECISION_SERIES_104 = ["match_attack_learned_decision_vs_attack_learned_600_104000",
                       "match_attack_learned_vs_attack_learned_decision_600_104030"]
DECISION_104_POOLED = [m.both_colours("attack-learned, learned decision vs attack-learned (commit 6c366aa)",
                                      DECISION_SERIES_104[0], DECISION_SERIES_104[1])]
#: the same under ``--realism realistic`` with the restart placement of commit 6c366aa (seeds 104200-104219)
DECISION_SERIES_REAL_104 = ["match_attack_learned_decision_vs_attack_learned_600_realistic_104200",
                            "match_attack_learned_vs_attack_learned_decision_600_realistic_104210"]
DECISION_REAL_104_POOLED = [
    m.both_colours("attack-learned, learned decision vs attack-learned, `--realism realistic` (commit 9b4d532)",
                   DECISION_SERIES_REAL_104[0], DECISION_SERIES_REAL_104[1])]
#: the same under ``--realism realistic`` with commit f0ad2a0 (the play code of 74a0018; seeds 100200-100219)
DECISION_SERIES_REAL_100 = ["match_attack_learned_decision_vs_attack_learned_600_realistic_100200",
                            "match_attack_learned_vs_attack_learned_decision_600_realistic_100210"]
DECISION_REAL_100_POOLED = [
    m.both_colours("attack-learned, learned decision vs attack-learned, `--realism realistic` (commit f0ad2a0)",
                   DECISION_SERIES_REAL_100[0], DECISION_SERIES_REAL_100[1])]
#: the retrained drill actor (blue only) and the improved decision (both colours) against the hand-coded decision
DECISION_SERIES_98 = ["match_attack_drill_v2_decision_vs_attack_learned_600_98000",
                      "match_attack_improved_decision_vs_attack_learned_600_98100",
                      "match_attack_learned_vs_attack_improved_decision_600_98130"]
DECISION_98_POOLED = [m.both_colours("attack-learned, improved decision vs attack-learned (commit e8e1dc0)",
                                     DECISION_SERIES_98[1], DECISION_SERIES_98[2])]
#: the learned decision on Division A against the hand-coded one, and against the no-pass baseline (commit 319a5ae)
DECISION_SERIES_97 = ["match_attack_learned_decision_vs_attack_learned_600_div_a_11v11_97000",
                      "match_attack_learned_vs_attack_learned_decision_600_div_a_11v11_97005",
                      "match_attack_learned_decision_vs_baseline_600_97100",
                      "match_baseline_vs_attack_learned_decision_600_97105",
                      "match_attack_learned_decision_vs_baseline_600_97110",
                      "match_baseline_vs_attack_learned_decision_600_97115"]
DECISION_97_POOLED = [
    m.both_colours("attack-learned, learned decision vs attack-learned, 11v11 Division A (commit 319a5ae)",
                   DECISION_SERIES_97[0], DECISION_SERIES_97[1]),
    ("attack-learned-decision vs baseline (commit 319a5ae)",
     ((DECISION_SERIES_97[2], "blue"), (DECISION_SERIES_97[3], "yellow"),
      (DECISION_SERIES_97[4], "blue"), (DECISION_SERIES_97[5], "yellow")))]
#: the team with the learned decision against the no-pass baseline, 11v11 Division A, plain and SSL format
DECISION_SERIES_DIV_A_102 = ["match_attack_learned_decision_vs_baseline_600_div_a_11v11_102000",
                             "match_baseline_vs_attack_learned_decision_600_div_a_11v11_102005",
                             "match_attack_learned_decision_vs_baseline_600_ssl_div_a_11v11_102100",
                             "match_baseline_vs_attack_learned_decision_600_ssl_div_a_11v11_102105",
                             "match_attack_learned_vs_baseline_600_div_a_11v11_102000",
                             "match_baseline_vs_attack_learned_600_div_a_11v11_102005"]
DECISION_DIV_A_102_POOLED = [
    m.both_colours("attack-learned-decision vs baseline, 11v11 Division A (commit 1155796)",
                   DECISION_SERIES_DIV_A_102[0], DECISION_SERIES_DIV_A_102[1]),
    m.both_colours("the same, `--format ssl` (halves, STOP, free kicks, fouls called)",
                   DECISION_SERIES_DIV_A_102[2], DECISION_SERIES_DIV_A_102[3]),
    m.both_colours("attack-learned (the cost decision) vs baseline, the seeds of the first row",
                   DECISION_SERIES_DIV_A_102[4], DECISION_SERIES_DIV_A_102[5])]
#: the learned carrier decision against the cost decision under SSL rules, 6v6 Division B, both colours (commit d8eae02)
DECISION_SSL_103 = ["match_attack_learned_decision_vs_attack_learned_600_ssl_103000",
                    "match_attack_learned_vs_attack_learned_decision_600_ssl_103005"]
DECISION_SSL_103_POOLED = [
    m.both_colours("attack-learned, learned decision vs attack-learned, `--format ssl`, 6v6 Division B",
                   DECISION_SSL_103[0], DECISION_SSL_103[1])]
#: the learned decision within SSL's dribbling limit against the cost decision, both colours (commit 360168e)
DECISION_SSL_105300 = ["match_attack_learned_decision_vs_attack_learned_600_ssl_105300",
                       "match_attack_learned_vs_attack_learned_decision_600_ssl_105310",
                       "match_attack_learned_decision_vs_attack_learned_600_ssl_105320",
                       "match_attack_learned_vs_attack_learned_decision_600_ssl_105330",
                       "match_attack_learned_decision_vs_attack_learned_600_ssl_105340",
                       "match_attack_learned_vs_attack_learned_decision_600_ssl_105350"]
DECISION_SSL_105300_POOLED = m.both_colours_rounds("learned decision (dribble limit) vs attack-learned, SSL format",
                                                   DECISION_SSL_105300, 105300)
#: the decision fine-tuned in the drill under SSL rules against the cost decision, both colours
DECISION_SSL_DRILL_105400 = ["match_attack_drill_ssl_decision_vs_attack_learned_600_ssl_105400",
                             "match_attack_learned_vs_attack_drill_ssl_decision_600_ssl_105410"]
DECISION_SSL_DRILL_105400_POOLED = [m.both_colours(
    "decision fine-tuned under SSL rules (`attack_drill_ssl.pt`) vs attack-learned, SSL format, 6v6 Division B",
    *DECISION_SSL_DRILL_105400)]
#: the decision fine-tuned against the match's defence against the cost decision, both colours
DECISION_DEFENDED_106900 = [name for lo in (106900, 106920, 106940) for name in (
    f"match_attack_drill_defended_decision_vs_attack_learned_600_ssl_{lo}",
    f"match_attack_learned_vs_attack_drill_defended_decision_600_ssl_{lo + 10}")]
DECISION_DEFENDED_106900_POOLED = m.both_colours_rounds(
    "decision fine-tuned against the match's defence (`attack_drill_defended.pt`) vs attack-learned, SSL format",
    DECISION_DEFENDED_106900, 106900)
#: the decision cloned from two teachers in the mixed drill against the cost decision, both colours (commit 229f9cc)
DECISION_MIX_107800 = [name for lo in (107800, 107820, 107840) for name in (
    f"match_attack_drill_mix_bc_decision_vs_attack_learned_600_ssl_{lo}",
    f"match_attack_learned_vs_attack_drill_mix_bc_decision_600_ssl_{lo + 10}")]
DECISION_MIX_107800_POOLED = m.both_colours_rounds(
    "decision cloned from two teachers in the mixed drill (`attack_drill_mix_bc.pt`) vs attack-learned, SSL format",
    DECISION_MIX_107800, 107800)
#: the clone shipped (commit 5847c51) under the realistic preset against the cost decision, 10 matches on each colour
DECISION_MIX_REALISTIC_107900 = ["match_attack_learned_decision_vs_attack_learned_600_ssl_realistic_107900",
                                 "match_attack_learned_vs_attack_learned_decision_600_ssl_realistic_107910"]
DECISION_MIX_REALISTIC_107900_POOLED = [m.both_colours(
    "attack-learned-decision (the clone, commit 5847c51) vs attack-learned, SSL format, `--realism realistic`",
    *DECISION_MIX_REALISTIC_107900)]
#: the same decision under the realistic preset, 10 matches on each colour (commit bdf646b)
DECISION_DEFENDED_REALISTIC_107000 = ["match_attack_drill_defended_decision_vs_attack_learned_600_ssl_realistic_107000",
                                      "match_attack_learned_vs_attack_drill_defended_decision_600_ssl_realistic_107010"]
DECISION_DEFENDED_REALISTIC_107000_POOLED = [m.both_colours(
    "decision fine-tuned against the match's defence vs attack-learned, SSL format, `--realism realistic`",
    *DECISION_DEFENDED_REALISTIC_107000)]
#: the attacking team with the shipped learned decision against the baseline team (commit c041229)
DECISION_SHIPPED_BASELINE_107100 = ["match_attack_learned_decision_vs_baseline_600_ssl_107100",
                                    "match_attack_learned_decision_vs_baseline_600_ssl_107110"]
DECISION_SHIPPED_BASELINE_107100_POOLED = [("attack-learned-decision vs baseline",
                                            tuple((n, "blue") for n in DECISION_SHIPPED_BASELINE_107100))]
#: the attacking-game targets with the shipped learned decision: realistic and Division A against the baseline,
#: against the passing team, self-play (commit c041229)
DECISION_SHIPPED_PASSING_107400 = ["match_attack_learned_decision_vs_passing_learned_600_ssl_107400"]
DECISION_SHIPPED_TARGETS_107500 = ["match_attack_learned_decision_vs_baseline_600_ssl_realistic_107500",
                                     "match_attack_learned_decision_vs_baseline_600_ssl_div_a_11v11_107600",
                                     "match_attack_learned_decision_selfplay_600_ssl_107700"]
#: the clone shipped as the learned decision: against the passing team (the clone as ``--blue-decision``, commit
#: fc0a0d9), the baseline team (20 matches), the attacking-game issue's other targets (commit c7b4a91)
DECISION_CLONE_PASSING_108100 = ["match_attack_drill_mix_bc_decision_vs_passing_learned_600_ssl_108100"]
DECISION_CLONE_BASELINE_108120 = ["match_attack_learned_decision_vs_baseline_600_ssl_108120",
                                  "match_attack_learned_decision_vs_baseline_600_ssl_108130"]
DECISION_CLONE_BASELINE_108120_POOLED = [("attack-learned-decision (the clone) vs baseline",
                                          tuple((n, "blue") for n in DECISION_CLONE_BASELINE_108120))]
DECISION_CLONE_DIV_A_108180 = ["match_attack_learned_decision_vs_attack_learned_600_ssl_div_a_11v11_108180",
                               "match_attack_learned_vs_attack_learned_decision_600_ssl_div_a_11v11_108183"]
DECISION_CLONE_DIV_A_108180_POOLED = [m.both_colours(
    "attack-learned-decision (the clone) vs attack-learned, 11v11 Division A, SSL format", *DECISION_CLONE_DIV_A_108180)]
#: the attacking plays' set-piece passes 0.6 m inside the field lines, with the clone (commit 26fde69)
RESTART_MARGIN_SELFPLAY_108200 = ["match_attack_learned_decision_selfplay_600_ssl_108200"]
RESTART_MARGIN_BASELINE_108220 = ["match_attack_learned_decision_vs_baseline_600_ssl_108220"]
RESTART_MARGIN_PASSING_108240 = ["match_attack_learned_decision_vs_passing_learned_600_ssl_108240"]
RESTART_MARGIN_DIV_A_108260 = ["match_attack_learned_decision_vs_baseline_600_ssl_div_a_11v11_108260"]
LONG_SHOT_DIV_A_108290 = ["match_attack_learned_decision_vs_baseline_600_ssl_div_a_11v11_108290"]
LONG_SHOT_BASELINE_108300 = ["match_attack_learned_decision_vs_baseline_600_ssl_108300"]
LONG_SHOT_OFF = ["match_attack_learned_decision_vs_baseline_600_ssl_div_a_11v11_108290_off",
                 "match_attack_learned_decision_vs_baseline_600_ssl_108300_off"]
#: (label, series with the long-shot rule, the same seeds without)
LONG_SHOT_PAIRED = [("11v11 Division A: with the long-shot rule (A) vs without (B)",
                     "match_attack_learned_decision_vs_baseline_600_ssl_div_a_11v11_108290",
                     "match_attack_learned_decision_vs_baseline_600_ssl_div_a_11v11_108290_off"),
                    ("6v6 Division B: with the long-shot rule (A) vs without (B)",
                     "match_attack_learned_decision_vs_baseline_600_ssl_108300",
                     "match_attack_learned_decision_vs_baseline_600_ssl_108300_off")]
#: the second defender only against a threat (ATTACK_DEFENDER_1_OPPONENTS 2, commit 18608a1) against the baseline
DEFENDER_1_BASELINE_108270 = ["match_attack_learned_decision_vs_baseline_600_ssl_108270"]
RESTART_MARGIN_BASELINE_108220_POOLED = [("attack-learned-decision (the clone), set-piece passes 0.6 m inside the lines, "
                                          "vs baseline", tuple((n, "blue") for n in RESTART_MARGIN_BASELINE_108220))]
DECISION_CLONE_TARGETS_108140 = ["match_attack_learned_decision_vs_baseline_600_ssl_realistic_108160",
                                 "match_attack_learned_decision_vs_baseline_600_ssl_div_a_11v11_108170",
                                 "match_attack_learned_decision_selfplay_600_ssl_108140"]
#: the shipped learned decision against the cost decision in 11v11 Division A, SSL format, both colours (commit c041229)
DECISION_SHIPPED_DIV_A_107300 = ["match_attack_learned_decision_vs_attack_learned_600_ssl_div_a_11v11_107300",
                                 "match_attack_learned_vs_attack_learned_decision_600_ssl_div_a_11v11_107310"]
DECISION_SHIPPED_DIV_A_107300_POOLED = [m.both_colours(
    "attack-learned-decision vs attack-learned, 11v11 Division A, SSL format", *DECISION_SHIPPED_DIV_A_107300)]
#: the improved decision with the second-iteration value actor against the cost decision, both colours (commit 646fe1b)
DECISION_IMPROVED_103 = ["match_attack_improved_decision_vs_attack_learned_600_103100",
                         "match_attack_learned_vs_attack_improved_decision_600_103105"]
DECISION_IMPROVED_103_POOLED = [
    m.both_colours("attack-learned, improved decision (second-iteration value actor) vs attack-learned",
                   DECISION_IMPROVED_103[0], DECISION_IMPROVED_103[1])]
#: the pressed-receive drills (RESULTS section 6, "Receive under pressure") and their training runs
RECEIVE_PRESSED = ["receive_pressed_baseline", "receive_pressed_learned", "receive_pressed_gated",
                   "receive_pressed_baseline_realistic", "receive_pressed_gated_realistic", "receive_gated_plain",
                   "receive_pressed_lane", "receive_pressed_lane_realistic", "receive_pressed_lane2",
                   "receive_pressed_lane2_realistic", "receive_lane2_plain", "receive_lane2_plain_div_a"]
RECEIVE_PRESSED_RUNS = ["receive_pressed_s0", "receive_pressed_bc1_s0", "receive_pressed_bc01_s0", "receive_pressed_gated_s0",
                        "receive_pressed_gated_s1", "receive_pressed_lane_s0"]
#: the attacking team with learned skills against itself with hand-coded skills, both colours
SKILLS_99100 = ["match_pressed_receive_vs_attack_baseline_600_99100", "match_attack_baseline_vs_pressed_receive_600_99130"]
SKILLS_99100_POOLED = [
    m.both_colours("attack-learned with the pressed receive, first gate, vs attack-baseline (commit 15af20f)",
                   SKILLS_99100[0], SKILLS_99100[1])]
SKILLS_99200 = ["match_attack_learned_vs_attack_baseline_600_99200", "match_attack_baseline_vs_attack_learned_600_99230"]
SKILLS_99200_POOLED = [
    m.both_colours("attack-learned (receive retrained under the lane gate) vs attack-baseline (commit 845ac88)",
                   SKILLS_99200[0], SKILLS_99200[1])]
SKILLS_99100_LANE = ["match_pressed_receive_lane_vs_attack_baseline_600_99100",
                     "match_attack_baseline_vs_pressed_receive_lane_600_99130"]
SKILLS_99110 = ["match_attack_learned_vs_attack_baseline_600_99110", "match_attack_baseline_vs_attack_learned_600_99140"]
SKILLS_99120 = ["match_attack_learned_vs_attack_baseline_600_99120", "match_attack_baseline_vs_attack_learned_600_99150"]
SKILLS_99100_LANE_POOLED = [
    m.both_colours("attack-learned with the pressed receive, lane gate, vs attack-baseline (commit 466a0c5)",
                   SKILLS_99100_LANE[0], SKILLS_99100_LANE[1]),
    m.both_colours("attack-learned (shipped pressed receive) vs attack-baseline (commit 17b2cca)",
                   SKILLS_99110[0], SKILLS_99110[1]),
    m.both_colours("attack-learned (shipped pressed receive) vs attack-baseline (commit ca1bd94)",
                   SKILLS_99120[0], SKILLS_99120[1]),
    ("the 40 with the shipped receive (seeds never used in tuning)",
     ((SKILLS_99110[0], "blue"), (SKILLS_99110[1], "yellow"),
      (SKILLS_99120[0], "blue"), (SKILLS_99120[1], "yellow"))),
    ("all 60", ((SKILLS_99100_LANE[0], "blue"), (SKILLS_99100_LANE[1], "yellow"),
                (SKILLS_99110[0], "blue"), (SKILLS_99110[1], "yellow"),
                (SKILLS_99120[0], "blue"), (SKILLS_99120[1], "yellow")))]
#: the learned decision vs the cost decision, 11v11 Division A, with the restart placement (seeds 104400-104409)
DECISION_SERIES_DIV_A_104 = ["match_attack_learned_decision_vs_attack_learned_600_div_a_11v11_104400",
                             "match_attack_learned_vs_attack_learned_decision_600_div_a_11v11_104405"]
DECISION_DIV_A_104_POOLED = [
    m.both_colours("attack-learned, learned decision vs attack-learned, 11v11 Division A (commit 1c05c72)",
                   DECISION_SERIES_DIV_A_104[0], DECISION_SERIES_DIV_A_104[1])]
#: "learned skills pay" again with the restart placement of 6c366aa (commit 1c05c72's worktree; seeds 104300-104359)
SKILLS_104300 = ["match_attack_learned_vs_attack_baseline_600_104300",
                 "match_attack_baseline_vs_attack_learned_600_104330"]
SKILLS_104300_POOLED = [m.both_colours("attack-learned vs attack-baseline (commit 1c05c72)",
                                       SKILLS_104300[0], SKILLS_104300[1])]
SKILLS_97200 = ["match_attack_learned_vs_attack_baseline_600_97200", "match_attack_baseline_vs_attack_learned_600_97230"]
SKILLS_97200_POOLED = [m.both_colours("attack-learned vs attack-baseline (commit e395ab2)",
                                      SKILLS_97200[0], SKILLS_97200[1])]
SKILLS_SSL_105200 = ["match_attack_learned_vs_attack_baseline_600_ssl_105200",
                     "match_attack_baseline_vs_attack_learned_600_ssl_105210",
                     "match_attack_learned_vs_attack_baseline_600_ssl_105220",
                     "match_attack_baseline_vs_attack_learned_600_ssl_105230",
                     "match_attack_learned_vs_attack_baseline_600_ssl_105240",
                     "match_attack_baseline_vs_attack_learned_600_ssl_105250"]
SKILLS_SSL_105200_POOLED = m.both_colours_rounds("attack-learned vs attack-baseline, SSL format", SKILLS_SSL_105200,
                                                 105200)
ATTACK_DRILL = [("hand-coded (the attacking plays' cost decision)", "attack_drill_handcoded"),
                ("learned (`mappo_attack_drill_bc_s0`: cloned, then MAPPO)",
                 "attack_drill_learned")]
ATTACK_DRILL_SELECTION = [("hand-coded", "tuning/attack_drill_handcoded_val49000"),
                          ("cloned hand-coded decision (`bc_attack_drill.pt`)", "tuning/attack_drill_bc_val49000"),
                          ("`mappo_attack_drill_bc_s0` at 1,678 decisions (its exported actor)", "tuning/attack_drill_s0_1678_val49000"),
                          ("`mappo_attack_drill_bc_s0` at 2,020 decisions", "tuning/attack_drill_s0_2020_val49000"),
                          ("`mappo_attack_drill_bc_s0` at 2,528 decisions", "tuning/attack_drill_s0_2528_val49000")]

#: the second fine-tuning run of the attack-drill decision: selection (seeds 49300-49599), then held out (44000)
ATTACK_DRILL_FT_SELECTION = [("hand-coded", "tuning/attack_drill_handcoded_val49300"),
                             ("learned, `mappo_attack_drill_bc_s0` actor", "tuning/attack_drill_shipped_val49300"),
                             ("`mappo_attack_drill_ft_s1` at 5,084 decisions", "tuning/attack_drill_ft_s1_5084_val49300"),
                             ("`mappo_attack_drill_ft_s1` at 7,098 decisions", "tuning/attack_drill_ft_s1_7098_val49300")]
#: display names of the value actors scored offline on the drill's tuning labels (seeds 49000-49299)
DEPARTURE_ACTORS = {
    "attack_drill_value_2nd.pt": "second iteration (`attack_drill_value_2nd.pt`)",
    "attack_drill_value_3rd.pt": "third iteration (`attack_drill_value_3rd.pt`)",
    "attack_drill_value_d0.pt": "first-decision labels, weight decay 1e-3, 300 epochs, seeds 0-2 merged (`attack_drill_value_d0.pt`)",
    **{f"v_{wd}_{ep}_s{s}.pt": f"first-decision labels, weight decay {wd}, {ep} epochs, seed {s}"
       for wd in ("1e-3", "1e-2", "3e-2") for ep in (100, 300) for s in (0, 1, 2)},
}
#: the attack drill's rollout values: the drill with the hand-coded chip pass and redirect (87714dd), then as in matches
ROLLOUT_VALUES = ("tuning/attack_drill_rollout_values_87714dd.json", "tuning/attack_drill_rollout_values.json")


def drill_vs_d0(tag: str) -> list[tuple[str, str]]:
    """The drill's hand-coded decision, the second-iteration and the first-decision value actors on one
    held-out run family (``attack_drill_<policy>_<tag>``)."""
    return [("hand-coded", f"attack_drill_handcoded_{tag}"),
            ("improved, second iteration (`attack_drill_value_2nd.pt`)", f"attack_drill_improved_2nd_{tag}"),
            ("improved, first-decision labels (`attack_drill_value_d0.pt`)", f"attack_drill_improved_d0_{tag}")]


def drill_vs_shipped(drill: str, seed: int) -> list[tuple[str, str]]:
    """A drill's hand-coded decision and the learned decision shipped before the clone on one held-out
    run family (``<drill>_handcoded_<seed>``, ``<drill>_learned_shipped_<seed>``)."""
    return [("hand-coded (the attacking plays' cost decision)", f"{drill}_handcoded_{seed}"),
            ("learned, fine-tuned against the match's defence (`attack_drill_defended.pt`, shipped as `attack_drill.pt` "
             "before the clone)",
             f"{drill}_learned_shipped_{seed}")]


#: the decision cloned from two teachers in attack-drill-mix (`bc_attack_drill_mix/attack_drill_mix_bc.pt`)
MIX_CLONE = "cloned from two teachers in attack-drill-mix (`attack_drill_mix_bc.pt`)"


def drill_vs_mix(drill: str, seed: int, shipped: str) -> list[tuple[str, str]]:
    """A drill's hand-coded decision, the shipped learned decision (its run ``shipped``) and the
    decision cloned in the mix (``<drill>_learned_mix_bc_<seed>``) on one held-out run family."""
    handcoded, (shipped_label, _) = drill_vs_shipped(drill, seed)
    return [handcoded, (shipped_label, shipped), (f"learned, {MIX_CLONE}", f"{drill}_learned_mix_bc_{seed}")]


def mix_selection(drill: str) -> list[tuple[str, str]]:
    """The candidates of the mix's selection on 300 validation episodes of one drill (seeds 47600-47899)."""
    d = "tuning/attack_drill_mix_selection"
    return [("hand-coded", f"{d}/handcoded_{drill}_47600"),
            ("the clone (`bc_attack_drill_mix`)", f"{d}/bc_clone_{drill}_47600"),
            ("`mappo_attack_drill_mix_s0`, final (12,004 decisions)", f"{d}/s0_final_{drill}_47600"),
            ("`mappo_attack_drill_mix_bc_s1`, best validation (6,597 decisions)", f"{d}/s1_6597_{drill}_47600"),
            ("`mappo_attack_drill_mix_bc_s1`, final (12,042 decisions)", f"{d}/s1_final_{drill}_47600")]


ATTACK_DRILL_RPI = [("hand-coded", "tuning/attack_drill_handcoded_val49000_87714dd"),
                    ("value actor, weight decay 1e-3 (`rollout_pi_attack_drill/a_1e-3_300.pt`)",
                     "tuning/attack_drill_rpi_wd1e-3_val49000"),
                    ("value actor, weight decay 1e-4 (`rollout_pi_attack_drill/a_1e-4_300.pt`)",
                     "tuning/attack_drill_rpi_wd1e-4_val49000")]
ATTACK_DRILL_44000 = [("hand-coded", "attack_drill_handcoded_44000"),
                      ("learned, `mappo_attack_drill_bc_s0` actor", "attack_drill_learned_44000"),
                      ("`mappo_attack_drill_ft_s1` at 7,098 decisions (not shipped)",
                       "attack_drill_learned_ft_s1_7098_44000")]

#: the README's first command over seeds 0-19: its match length and the lengths around it
README_GOAL_RATE = ["readme_match_selfplay_300", "readme_match_selfplay_450", "readme_match_selfplay_600",
                    "readme_match_selfplay_450_fed7dee", "readme_match_learned_decision_360",
                    "readme_match_learned_decision_360_5847c51", "readme_match_learned_decision_450_5847c51",
                    "readme_match_learned_decision_450_26fde69"]

TABLES: dict[str, Callable[[Path], list[str]]] = {
    "skills_paper": lambda r: t.skills(r, SKILLS_PAPER),
    "skills_tracker_div_a": lambda r: t.skills(r, SKILLS_TRACKER),
    "skills_randomized": lambda r: t.skills(r, SKILLS_RANDOMIZED),
    "selection": lambda r: t.selection(r, ["aim_to_shoot_full_s0", "go_to_ball_fast_s1", "go_to_ball_s0",
                                           "gtb_both_s0"]),
    "td3_vs_ddpg": lambda r: t.training_compare(r, ["go_to_ball_fast_s1", "go_to_ball_td3_s1"], 10_000, 80_000),
    "go_to_ball_fast": lambda r: t.training_compare(r, ["go_to_ball_s0", "gtb_fast_s0", "gtb_fast_u025_s0",
                                                       "gtb_fast_u025_t2_s0"], 40_000, 200_010),
    "go_to_ball_both_fields": lambda r: t.selection_by_field(r, "gtb_both_s0"),
    "tactic": lambda r: t.tactics(r, TACTIC),
    "dribble": lambda r: t.tactics(r, DRIBBLE),
    "tracker_errors": t.tracker_errors,
    "tracker_pairs": lambda r: t.tracker_pairs(r, TRACKER_PAIRS),
    "passing_skills": lambda r: t.skills(r, PASSING_SKILLS),
    "pass_endurance": lambda r: t.drills(r, PASS_ENDURANCE),
    "redirect_skills": lambda r: t.skills(r, REDIRECT_SKILLS),
    "chip_pass_skills": lambda r: t.skills(r, CHIP_PASS_SKILLS),
    "chip_pass_selection": lambda r: t.selection(r, ["chip_pass_bc2k_s0", "chip_pass_bc100_s0"]),
    "passing_series": lambda r: m.series(r, PASSING_SERIES),
    "series_600_formats": lambda r: m.series_600(r, SERIES_600_SSL),
    "readme_goal_rate": lambda r: m.goal_rate(r, README_GOAL_RATE),
    "attack_series": lambda r: m.series_600(r, ATTACK_SERIES),
    "decision_series": lambda r: m.series_600(r, DECISION_SERIES),
    "decision_series_fair": lambda r: m.series_600(r, DECISION_SERIES_FAIR),
    "decision_fair_pooled": lambda r: m.pooled_sides(r, DECISION_FAIR_POOLED),
    "decision_series_fair2": lambda r: m.series_600(r, DECISION_SERIES_FAIR2),
    "decision_series_press": lambda r: m.series_600(r, DECISION_SERIES_PRESS),
    "decision_press_pooled": lambda r: m.pooled_sides(r, DECISION_PRESS_POOLED),
    "decision_series_99": lambda r: m.series_600(r, DECISION_SERIES_99),
    "decision_99_pooled": lambda r: m.pooled_sides(r, DECISION_99_POOLED),
    "decision_series_104": lambda r: m.series_600(r, DECISION_SERIES_104),
    "decision_104_pooled": lambda r: m.pooled_sides(r, DECISION_104_POOLED),
    "decision_series_real_104": lambda r: m.series_600(r, DECISION_SERIES_REAL_104),
    "decision_real_104_pooled": lambda r: m.pooled_sides(r, DECISION_REAL_104_POOLED),
    "decision_series_real_100": lambda r: m.series_600(r, DECISION_SERIES_REAL_100),
    "decision_real_100_pooled": lambda r: m.pooled_sides(r, DECISION_REAL_100_POOLED),
    "decision_series_97": lambda r: m.series_600(r, DECISION_SERIES_97),
    "decision_series_98": lambda r: m.series_600(r, DECISION_SERIES_98),
    "decision_98_pooled": lambda r: m.pooled_sides(r, DECISION_98_POOLED),
    "decision_series_improved_103": lambda r: m.series_600(r, DECISION_IMPROVED_103),
    "decision_improved_103_pooled": lambda r: m.pooled_sides(r, DECISION_IMPROVED_103_POOLED),
    "decision_97_pooled": lambda r: m.pooled_sides(r, DECISION_97_POOLED),
    "decision_series_div_a_102": lambda r: m.series_600(r, DECISION_SERIES_DIV_A_102),
    "decision_div_a_102_pooled": lambda r: m.pooled_sides(r, DECISION_DIV_A_102_POOLED),
    "decision_series_ssl_103": lambda r: m.series_600(r, DECISION_SSL_103),
    "decision_ssl_103_pooled": lambda r: m.pooled_sides(r, DECISION_SSL_103_POOLED),
    "decision_series_ssl_106900": lambda r: m.series_600(r, DECISION_DEFENDED_106900),
    "decision_ssl_106900_pooled": lambda r: m.pooled_sides(r, DECISION_DEFENDED_106900_POOLED),
    "decision_series_ssl_mix_107800": lambda r: m.series_600(r, DECISION_MIX_107800),
    "decision_ssl_mix_107800_pooled": lambda r: m.pooled_sides(r, DECISION_MIX_107800_POOLED),
    "decision_series_realistic_107000": lambda r: m.series_600(r, DECISION_DEFENDED_REALISTIC_107000),
    "decision_realistic_107000_pooled": lambda r: m.pooled_sides(r, DECISION_DEFENDED_REALISTIC_107000_POOLED),
    "decision_shipped_baseline_107100": lambda r: m.series_600(r, DECISION_SHIPPED_BASELINE_107100),
    "decision_shipped_baseline_107100_pooled": lambda r: m.pooled_attack(r, DECISION_SHIPPED_BASELINE_107100_POOLED),
    "decision_shipped_div_a_107300": lambda r: m.series_600(r, DECISION_SHIPPED_DIV_A_107300),
    "decision_shipped_div_a_107300_pooled": lambda r: m.pooled_sides(r, DECISION_SHIPPED_DIV_A_107300_POOLED),
    "league_ssl_107200": lambda r: m.league(r, "league_ssl_107200"),
    "league_ssl_108000": lambda r: m.league(r, "league_ssl_108000"),
    "decision_mix_realistic_107900": lambda r: m.series_600(r, DECISION_MIX_REALISTIC_107900),
    "decision_mix_realistic_107900_pooled": lambda r: m.pooled_sides(r, DECISION_MIX_REALISTIC_107900_POOLED),
    "decision_shipped_baseline_targets_107500": lambda r: m.series_600(r, DECISION_SHIPPED_TARGETS_107500),
    "decision_shipped_passing_107400": lambda r: m.series_600(r, DECISION_SHIPPED_PASSING_107400),
    "decision_clone_passing_108100": lambda r: m.series_600(r, DECISION_CLONE_PASSING_108100),
    "decision_clone_baseline_108120": lambda r: m.series_600(r, DECISION_CLONE_BASELINE_108120),
    "decision_clone_baseline_108120_pooled": lambda r: m.pooled_attack(r, DECISION_CLONE_BASELINE_108120_POOLED),
    "decision_clone_targets_108140": lambda r: m.series_600(r, DECISION_CLONE_TARGETS_108140),
    "set_piece_margin_probe": lambda r: m.pass_losses_by_play([r / "tuning" / "set_piece_margin_0.15.json",
                                                               r / "tuning" / "set_piece_margin_0.6.json"]),
    "restart_margin_selfplay_108200": lambda r: m.series_600(r, RESTART_MARGIN_SELFPLAY_108200),
    "restart_margin_baseline_108220": lambda r: m.series_600(r, RESTART_MARGIN_BASELINE_108220),
    "restart_margin_passing_108240": lambda r: m.series_600(r, RESTART_MARGIN_PASSING_108240),
    "restart_margin_div_a_108260": lambda r: m.series_600(r, RESTART_MARGIN_DIV_A_108260),
    "defender_1_baseline_108270": lambda r: m.series_600(r, DEFENDER_1_BASELINE_108270),
    "long_shot_div_a_108290": lambda r: m.series_600(r, LONG_SHOT_DIV_A_108290),
    "long_shot_baseline_108300": lambda r: m.series_600(r, LONG_SHOT_BASELINE_108300),
    "long_shot_off": lambda r: m.series_600(r, LONG_SHOT_OFF),
    "long_shot_paired": lambda r: m.paired_series(r, LONG_SHOT_PAIRED),
    "restart_margin_baseline_108220_pooled": lambda r: m.pooled_attack(r, RESTART_MARGIN_BASELINE_108220_POOLED),
    "decision_clone_div_a_108180": lambda r: m.series_600(r, DECISION_CLONE_DIV_A_108180),
    "decision_clone_div_a_108180_pooled": lambda r: m.pooled_sides(r, DECISION_CLONE_DIV_A_108180_POOLED),
    "decision_series_ssl_105400": lambda r: m.series_600(r, DECISION_SSL_DRILL_105400),
    "decision_ssl_105400_pooled": lambda r: m.pooled_sides(r, DECISION_SSL_DRILL_105400_POOLED),
    "decision_series_ssl_105300": lambda r: m.series_600(r, DECISION_SSL_105300),
    "decision_ssl_105300_pooled": lambda r: m.pooled_sides(r, DECISION_SSL_105300_POOLED),
    "receive_pressed": lambda r: t.skills(r, RECEIVE_PRESSED),
    "receive_pressed_selection": lambda r: t.selection(r, RECEIVE_PRESSED_RUNS),
    "receive_mixed_selection_s0": lambda r: t.selection_by_field(r, "receive_pressed_mixed_s0"),
    "receive_mixed_selection_s1": lambda r: t.selection_by_field(r, "receive_pressed_mixed_s1"),
    "skills_99100": lambda r: m.series_600(r, SKILLS_99100),
    "skills_99100_pooled": lambda r: m.pooled_sides(r, SKILLS_99100_POOLED),
    "skills_99100_lane": lambda r: m.series_600(r, SKILLS_99100_LANE + SKILLS_99110 + SKILLS_99120),
    "skills_99100_lane_pooled": lambda r: m.pooled_sides(r, SKILLS_99100_LANE_POOLED),
    "skills_99200": lambda r: m.series_600(r, SKILLS_99200),
    "skills_99200_pooled": lambda r: m.pooled_sides(r, SKILLS_99200_POOLED),
    "decision_series_div_a_104": lambda r: m.series_600(r, DECISION_SERIES_DIV_A_104),
    "decision_div_a_104_pooled": lambda r: m.pooled_sides(r, DECISION_DIV_A_104_POOLED),
    "skills_104300": lambda r: m.series_600(r, SKILLS_104300),
    "skills_104300_pooled": lambda r: m.pooled_sides(r, SKILLS_104300_POOLED),
    "skills_97200": lambda r: m.series_600(r, SKILLS_97200),
    "skills_97200_pooled": lambda r: m.pooled_sides(r, SKILLS_97200_POOLED),
    "skills_ssl_105200": lambda r: m.series_600(r, SKILLS_SSL_105200),
    "skills_ssl_105200_pooled": lambda r: m.pooled_sides(r, SKILLS_SSL_105200_POOLED),
    "attack_targets": lambda r: m.series_600(r, ATTACK_TARGETS),
    "attack_targets_skills": lambda r: m.series_600(r, ATTACK_TARGETS_SKILLS),
    "attack_targets_fair": lambda r: m.series_600(r, ATTACK_TARGETS_FAIR),
    "attack_targets_fair_pooled": lambda r: m.pooled_attack(r, ATTACK_TARGETS_FAIR_POOLED),
    "attack_targets_press": lambda r: m.series_600(r, ATTACK_TARGETS_PRESS),
    "attack_targets_press_pooled": lambda r: m.pooled_attack(r, ATTACK_TARGETS_PRESS_POOLED),
    "attack_targets_99": lambda r: m.series_600(r, ATTACK_TARGETS_99),
    "attack_targets_99_pooled": lambda r: m.pooled_attack(r, ATTACK_TARGETS_99_POOLED),
    "colour_balance": lambda r: m.colour_balance(r, COLOUR_BALANCE),
    "colour_mirror": lambda r: m.colour_mirror(r, ["colour_mirror_attack_baseline.json",
                                                   "colour_mirror_attack_learned.json"]),
    "match_variants": lambda r: m.match_variants(r, MATCH_VARIANTS),
    "set_piece_variants_selfplay": lambda r: m.selfplay_variants(r, SET_PIECE_VARIANTS_SELFPLAY),
    "set_piece_chip_selfplay": lambda r: m.selfplay_variants(r, SET_PIECE_CHIP_SELFPLAY),
    "match_variants_defender_1": lambda r: m.match_variants(r, MATCH_VARIANTS_DEFENDER_1),
    "match_variants_defence": lambda r: m.match_variants(r, MATCH_VARIANTS_DEFENCE),
    "match_variants_ssl_marks": lambda r: m.match_variants(r, MATCH_VARIANTS_SSL_MARKS),
    "match_variants_ssl_opp_area": lambda r: m.match_variants(r, MATCH_VARIANTS_SSL_OPP_AREA, fouls=True),
    "match_variants_ssl_scoring": lambda r: m.match_variants(r, MATCH_VARIANTS_SSL_SCORING, fouls=True),
    "foul_probe": lambda r: m.foul_probe(r, FOUL_PROBES),
    "match_variants_selfplay_pass": lambda r: m.match_variants(r, MATCH_VARIANTS_SELFPLAY_PASS),
    "match_variants_selfplay_arrive": lambda r: m.match_variants(r, MATCH_VARIANTS_SELFPLAY_ARRIVE),
    "match_variants_shots": lambda r: m.match_variants(r, MATCH_VARIANTS_SHOTS),
    "match_variants_div_a": lambda r: m.match_variants(r, MATCH_VARIANTS_DIV_A),
    "match_variants_div_a_keep": lambda r: m.match_variants(r, MATCH_VARIANTS_DIV_A_KEEP),
    "match_variants_div_a_tap": lambda r: m.match_variants(r, MATCH_VARIANTS_DIV_A_TAP),
    "match_variants_div_a_long_shot": lambda r: m.match_variants(r, MATCH_VARIANTS_DIV_A_LONG_SHOT),
    "shot_outcomes_ssl": lambda r: m.shot_outcomes([r / "tuning" / "shot_outcome_probe_ssl_div_a.json",
                                                    r / "tuning" / "shot_outcome_probe_ssl_div_b.json"]),
    "wall_probe": lambda r: m.wall_probe(r / "tuning" / "wall_probe.json"),
    "shot_outcomes": lambda r: m.shot_outcomes(r / "tuning" / "shot_outcome_probe.json"),
    "pass_losses": lambda r: m.pass_losses([r / "tuning" / "pass_loss_probe_d8f659c.json",
                                            r / "tuning" / "pass_loss_probe_any_speed.json",
                                            r / "tuning" / "pass_loss_probe.json"]),
    "pass_losses_ssl": lambda r: m.pass_losses_by_play([r / "tuning" / "pass_loss_probe_ssl_selfplay.json",
                                                        r / "tuning" / "pass_loss_probe_ssl_baseline.json"]),
    "pass_options": lambda r: m.pass_options(r, ["pass_option_probe.json", "pass_option_probe_guard1.json"]),
    "set_piece_series": lambda r: m.set_piece_series(r, SET_PIECE_SERIES),
    "ssl_fouls_104100": lambda r: m.ssl_fouls_series(r, SSL_FOULS_104100),
    "set_piece_probe": lambda r: m.set_piece_probe(r, ["set_piece_probe_6b6ee3b.json",
                                                       "set_piece_probe_passing_6b6ee3b.json"]),
    "set_piece_probe_kicked": lambda r: m.set_piece_probe(r, ["set_piece_probe.json", "set_piece_probe_passing.json"]),
    "ssl_set_pieces_104100": lambda r: m.ssl_fouls_series(r, SSL_SET_PIECES_104100),
    "attack_targets_ssl_104600": lambda r: m.series_600(r, ATTACK_TARGETS_SSL_104600),
    "attack_targets_ssl_104600_set_pieces": lambda r: m.set_piece_series(r, ATTACK_TARGETS_SSL_104600),
    "attack_realistic_ssl_105500": lambda r: m.series_600(r, ATTACK_REALISTIC_SSL_105500),
    "attack_targets_ssl_105600": lambda r: m.series_600(r, ATTACK_TARGETS_SSL_105600),
    "attack_targets_ssl_105600_set_pieces": lambda r: m.set_piece_series(r, ATTACK_TARGETS_SSL_105600),
    "attack_ssl_106200": lambda r: m.series_600(r, ATTACK_SSL_106200),
    "attack_ssl_106200_pooled": lambda r: m.pooled_attack(r, ATTACK_SSL_106200_POOLED),
    "attack_ssl_106200_fouls": lambda r: m.ssl_fouls_series(r, ATTACK_SSL_106200_FOULS),
    "ssl_set_pieces_vs_passing_104500": lambda r: m.ssl_fouls_series(r, [(
        "set pieces kicked, walls", "match_attack_learned_vs_passing_learned_600_ssl_104500")]),
    "attack_skill_swaps": lambda r: m.series_600(r, ATTACK_SKILL_SWAPS),
    "attack_skill_swaps_98": lambda r: m.series_600(r, ATTACK_SKILL_SWAPS_98),
    "go_to_ball_rolling_selection": lambda r: t.rolling_selection(r, {
        f: [f"tuning/go_to_ball_rolling_val5000_{f}.json", f"tuning/go_to_ball_rolling_val5000_{f}_2.json"]
        for f in ("div_b", "div_a")}),
    "go_to_ball_rolling": lambda r: t.rolling_probe(r, [f"go_to_ball_rolling/probe_{f}_{m}.json"
                                                        for f in ("div_b", "div_a") for m in ("none", "realistic")],
                                                    ROLLING_ACTOR),
    "league_anchors": lambda r: m.league(r, "league_anchors"),
    "league_learned": lambda r: m.league(r, "league_learned"),
    "league_96000": lambda r: m.league(r, "league_96000"),
    "league_100000": lambda r: m.league(r, "league_100000"),
    "league_ssl_105100": lambda r: m.league(r, "league_ssl_105100"),
    "league_ssl_106100": lambda r: m.league(r, "league_ssl_106100"),
    "passing_contested_kick": lambda r: m.tuning(r, [("`contested_kick` on", "passing_contested_kick.json",
                                                      "contested_kick_on"),
                                                     ("`contested_kick` off (the default)",
                                                      "passing_contested_kick.json", "contested_kick_off")]),
    "passing_skill_swaps": lambda r: m.tuning(r, [
        ("all learned (`passing-learned`)", "ablation_all_learned.json", None),
        ("go-to-ball hand-coded, others learned", "ablation_gtb_baseline.json", None),
        ("pass and receive hand-coded, others learned", "ablation_pass_receive_baseline.json", None),
        ("all learned, 40 more matches", "learned_vs_passing_baseline_45320.json", None),
        ("all learned, self-play with the coordinator's counters", "selfplay_pass_counters.json", None)]),
    "keepaway": lambda r: t.keepaway(r, KEEPAWAY),
    "attack": lambda r: t.attack(r, ATTACK),
    "attack_drill": lambda r: t.attack(r, ATTACK_DRILL),
    "attack_drill_selection": lambda r: t.attack(r, ATTACK_DRILL_SELECTION),
    "attack_drill_ft_selection": lambda r: t.attack(r, ATTACK_DRILL_FT_SELECTION),
    "attack_drill_44000": lambda r: t.attack(r, ATTACK_DRILL_44000),
    "attack_drill_rollout_pi": lambda r: t.attack(r, ATTACK_DRILL_RPI),
    "attack_drill_shoot_threshold": lambda r: t.probe_rows(r / "tuning" / "attack_drill_shoot_threshold.json",
                                                           "shoot_threshold"),
    "attack_drill_42000": lambda r: t.attack(r, [("hand-coded", "attack_drill_handcoded_42000"),
                                                 ("learned, `mappo_attack_drill_bc_s0` actor", "attack_drill_learned_42000"),
                                                 ("learned, retrained in the fixed drill (`mappo_attack_drill_v2_s0`, not shipped)",
                                                  "attack_drill_learned_v2_42000"),
                                                 ("improved: hand-coded, the value actor's option at the first decision "
                                                  "(first iteration, `attack_drill_value_1st.pt`)", "attack_drill_improved_42000")]),
    "attack_drill_realistic_42000": lambda r: t.attack(r, [("hand-coded", "attack_drill_handcoded_realistic"),
                                                           ("learned, `mappo_attack_drill_bc_s0` actor", "attack_drill_learned_realistic"),
                                                           ("improved (first iteration, `attack_drill_value_1st.pt`, at the first decision)",
                                                            "attack_drill_improved_realistic")]),
    "attack_drill_first_decision": lambda r: t.probe_rows(r / "tuning" / "attack_drill_first_decision.json", "policy"),
    "attack_drill_iterations": lambda r: t.probe_rows(r / "tuning" / "attack_drill_iterations.json",
                                                            "policy"),
    "attack_drill_150000": lambda r: t.attack(r, [("hand-coded", "attack_drill_handcoded_150000"),
                                                  ("improved, first iteration (`attack_drill_value_1st.pt`)",
                                                   "attack_drill_improved_150000"),
                                                  ("improved, second iteration (`attack_drill_value_2nd.pt`)",
                                                   "attack_drill_improved_2nd_150000")]),
    "attack_drill_151000": lambda r: t.attack(r, [("hand-coded", "attack_drill_handcoded_151000"),
                                                  ("improved, second iteration (`attack_drill_value_2nd.pt`)",
                                                   "attack_drill_improved_2nd_151000"),
                                                  ("improved, third iteration (`attack_drill_value_3rd.pt`, not shipped)",
                                                   "attack_drill_improved_3rd_151000")]),
    "attack_drill_div_a_150000": lambda r: t.attack(r, [("hand-coded", "attack_drill_handcoded_div_a_150000"),
                                                        ("improved, second iteration (`attack_drill_value_2nd.pt`)",
                                                         "attack_drill_improved_2nd_div_a_150000")]),
    "attack_drill_realistic_150000": lambda r: t.attack(r, [("hand-coded", "attack_drill_handcoded_realistic_150000"),
                                                            ("improved, second iteration (`attack_drill_value_2nd.pt`)",
                                                             "attack_drill_improved_2nd_realistic_150000")]),
    "attack_drill_first_decision_values": lambda r: t.rollout_values(
        [r / "tuning" / "attack_drill_rollout_values_d0.json", r / "tuning" / "attack_drill_rollout_values_49000.json"],
        "decision"),
    "attack_drill_departures_49000": lambda r: t.departure_scores(r / "tuning" / "attack_drill_departures_49000.json",
                                                                  DEPARTURE_ACTORS),
    "attack_drill_152000": lambda r: t.attack(r, drill_vs_d0("152000")),
    "attack_drill_d0_150000": lambda r: t.attack(r, drill_vs_d0("150000")),
    "attack_drill_d0_realistic_150000": lambda r: t.attack(r, drill_vs_d0("realistic_150000")),
    "attack_drill_d0_div_a_150000": lambda r: t.attack(r, drill_vs_d0("div_a_150000")),
    "attack_drill_aim": lambda r: t.probe_rows(r / "tuning" / "attack_drill_aim.json", "rule"),
    "attack_drill_rollout_values": lambda r: t.rollout_values([r / f for f in ROLLOUT_VALUES], "decision"),
    "attack_drill_rollout_choices": lambda r: t.rollout_values([r / f for f in ROLLOUT_VALUES], "choice"),
    "mappo_attack_match": lambda r: t.mappo_runs(r, [("mappo_attack_match_s0", ""), ("mappo_attack_match_clone_s1", ""),
                                                     ("mappo_attack_match_clone_ent_s2", "")], None, "goal"),
    "mappo_attack_drill": lambda r: t.mappo_runs(r, [("mappo_attack_drill_bc_s0", "attack_drill_learned")],
                                                 "attack_drill_handcoded", "goal"),
    "mappo_attack_drill_v2": lambda r: t.mappo_runs(r, [("mappo_attack_drill_v2_s0", "attack_drill_learned_v2_42000")],
                                                    "attack_drill_handcoded_42000", "goal"),
    "attack_drill_ssl_153000": lambda r: t.attack(r, [
        ("hand-coded (the attacking plays' cost decision)", "attack_drill_ssl_handcoded_153000"),
        ("learned, `mappo_attack_drill_bc_s0` actor (trained in the drill without fouls)", "attack_drill_ssl_learned_153000"),
        ("learned, fine-tuned under SSL rules (`mappo_attack_drill_ssl_s0`, `attack_drill_ssl.pt`)",
         "attack_drill_ssl_learned_ssl_153000")]),
    "attack_drill_shipped_152000": lambda r: t.attack(r, drill_vs_shipped("attack_drill", 152000)),
    "attack_drill_mix_selection_ssl": lambda r: t.attack(r, mix_selection("attack-drill-ssl")),
    "attack_drill_mix_selection_defended": lambda r: t.attack(r, mix_selection("attack-drill-defended")),
    "mappo_attack_drill_mix": lambda r: t.mappo_runs(
        r, [("mappo_attack_drill_mix_s0", ""), ("mappo_attack_drill_mix_bc_s1", "")], None, "goal"),
    "attack_drill_mix_152000": lambda r: t.attack(r, drill_vs_mix("attack_drill", 152000,
                                                                  "attack_drill_learned_shipped_152000")),
    "attack_drill_ssl_mix_153000": lambda r: t.attack(r, drill_vs_mix("attack_drill_ssl", 153000,
                                                                      "attack_drill_ssl_learned_shipped_153000")),
    "attack_drill_defended_mix_154000": lambda r: t.attack(r, drill_vs_mix(
        "attack_drill_defended", 154000, "attack_drill_defended_learned_defended_154000")),
    "attack_drill_ssl_shipped_153000": lambda r: t.attack(r, drill_vs_shipped("attack_drill_ssl", 153000)),
    "attack_drill_ssl_157000": lambda r: t.attack(r, [
        ("hand-coded (the attacking plays' cost decision)", "attack_drill_ssl_handcoded_157000"),
        (f"learned, {MIX_CLONE}", "attack_drill_ssl_learned_mix_bc_157000"),
        ("learned, MAPPO from the clone in attack-drill-mix (`mappo_attack_drill_mix_bc_s1`, final snapshot "
         "`actor-12042.pt`)", "attack_drill_ssl_learned_mix_ft_157000")]),
    "mappo_attack_drill_ssl": lambda r: t.mappo_runs(r, [("mappo_attack_drill_ssl_s0", "attack_drill_ssl_learned_ssl_153000")],
                                                     "attack_drill_ssl_handcoded_153000", "goal"),
    "attack_drill_defended_154000": lambda r: t.attack(r, [
        ("hand-coded (the attacking plays' cost decision)", "attack_drill_defended_handcoded_154000"),
        ("learned, `mappo_attack_drill_bc_s0` actor (trained in the drill against a goalie and one defender)",
         "attack_drill_defended_learned_154000"),
        ("learned, fine-tuned under SSL rules (`attack_drill_ssl.pt`)", "attack_drill_defended_learned_ssl_154000"),
        ("learned, fine-tuned against the match's defence (`mappo_attack_drill_defended_s1`, `attack_drill_defended.pt`)",
         "attack_drill_defended_learned_defended_154000")]),
    "attack_drill_defended_selection": lambda r: t.attack(r, [
        ("seed 0, 18,035 decisions", "tuning/attack_drill_defended_selection/val_s0_48600"),
        ("seed 1, 12,029 decisions", "tuning/attack_drill_defended_selection/val_s1_48600")]),
    "mappo_attack_drill_defended": lambda r: t.mappo_runs(
        r, [("mappo_attack_drill_defended_s0", ""),
            ("mappo_attack_drill_defended_s1", "attack_drill_defended_learned_defended_154000")],
        "attack_drill_defended_handcoded_154000", "goal"),
    "drill_end_probe_155000": lambda r: t.drill_ends([
        ("hand-coded", r / "tuning" / "drill_end_probe" / "handcoded_155000.json"),
        ("`mappo_attack_drill_bc_s0` actor", r / "tuning" / "drill_end_probe" / "learned_155000.json"),
        ("fine-tuned under SSL rules (`attack_drill_ssl.pt`)", r / "tuning" / "drill_end_probe" / "learned_ssl_155000.json"),
        ("fine-tuned against the match's defence (`attack_drill_defended.pt`)",
         r / "tuning" / "drill_end_probe" / "learned_defended_155000.json")]),
    "decision_tasks_realistic": lambda r: t.decision_tasks(r, "*_realistic*"),
    "mappo_keepaway": lambda r: t.mappo_runs(r, [("mappo_keepaway_s0", "keepaway_learned_s0"),
                                                 ("mappo_keepaway_s1", "keepaway_learned"),
                                                 ("mappo_keepaway_s2", "keepaway_learned_s2")],
                                             "keepaway_handcoded", "duration"),
    "mappo_attack": lambda r: t.mappo_runs(r, [(f"mappo_attack{k}_s{s}", "") for k in ("-3v2", "_bc", "_snap_bc")
                                               for s in (0, 1, 2)], None, "goal"),
    "pass_and_score": t.pass_and_score,
}

MARKER = re.compile(r"(<!-- table:([\w-]+) -->\n)(.*?)(<!-- /table:\2 -->)", re.S)


def render(name: str, results: Path) -> str:
    return "\n".join(TABLES[name](results)) + "\n"


def regenerate(doc_text: str, results: Path) -> tuple[str, list[str]]:
    """The doc with every marked table regenerated, and the problems found: names of
    tables whose text changed, markers without a table, tables without a marker."""
    changed: list[str] = []
    seen: set[str] = set()

    def fill(m: re.Match) -> str:
        name = m.group(2)
        seen.add(name)
        if name not in TABLES:
            changed.append(f"{name} (no such table)")
            return m.group(0)
        body = render(name, results)
        if body != m.group(3):
            changed.append(name)
        return m.group(1) + body + m.group(4)

    text = MARKER.sub(fill, doc_text)
    changed += [f"{n} (no marker in the doc)" for n in TABLES if n not in seen]
    return text, changed


def main(argv: list[str] | None = None) -> int:
    p = argparse.ArgumentParser(prog="python -m train.report", description=__doc__,
                                formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--results", default="results", type=Path, help="folder of result records (default results)")
    p.add_argument("--doc", default="docs/RESULTS.md", type=Path, help="document to fill (default docs/RESULTS.md)")
    p.add_argument("--check", action="store_true", help="change nothing; exit 1 if a table would change")
    p.add_argument("--print", dest="show", metavar="NAME", choices=sorted(TABLES), help="print one table and exit")
    a = p.parse_args(argv)
    if a.show:
        print(render(a.show, a.results), end="")
        return 0
    old = a.doc.read_text()
    new, changed = regenerate(old, a.results)
    if a.check:
        for c in changed:
            print(f"{a.doc}: table {c} differs from the records")
        return 1 if changed else 0
    if new != old:
        atomic_write_bytes(a.doc, new.encode())
    print(f"{a.doc}: {len(TABLES)} tables" + (f", rewritten: {', '.join(changed)}" if changed else ", unchanged"))
    return 0


if __name__ == "__main__":
    sys.exit(main())
