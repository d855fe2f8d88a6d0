"""Export a learned-skill actor to ONNX, for SSL team software in C++ or Rust.

    ssl-marl export-onnx ssl_marl/skills/pretrained/go_to_ball.pt go_to_ball.onnx

The model has one input ``obs`` (batch, obs_dim) float32 and one output
``action`` (batch, act_dim) float32 in [-1, 1] (the actor's tanh output, the
*task* action of the skill's Gymnasium env). Everything a deployment needs to
build the input and read the output is stored as string ``metadata_props``:

* ``ssl_marl.obs_spec``: observation spec version (e.g. ``go_to_ball/v1``); the
  network is valid only for features built exactly as that spec says;
* ``ssl_marl.obs_names``: JSON list naming each input column (team frame /
  robot frame, SI units; see :mod:`ssl_marl.skills.features`);
* ``ssl_marl.obs_normalisation``: JSON ``{"kind": "none", ...}``: the features
  are fed raw (metres, m/s, rad/s, sin/cos); no mean/std is applied;
* ``ssl_marl.action_names`` / ``ssl_marl.action_low`` / ``ssl_marl.action_high``:
  what each output column means and the env's action bounds;
* ``ssl_marl.action_form``: JSON saying how the output becomes the robot's command
  (:func:`action_form_of`): ``{"kind": "direct"}`` for most specs; for a residual spec
  (``receive/v2``, ``receive/v3``, ``redirect/v2``) the hand-coded controller it corrects,
  the rule that combines them and, for ``receive/v3``, the gate outside which the
  hand-coded action alone is sent; for ``redirect/v3`` the aim point it chooses;
* ``ssl_marl.metadata``: the checkpoint's full metadata as JSON (skill, seed,
  samples, hyper-parameters, git commit).

Needs the optional ``onnx`` extra (``pip install -e ".[onnx]"``: ``onnx`` for the
exporter and model checks, ``onnxruntime`` to run the result).
"""

from __future__ import annotations

import io
import json
import os
import warnings
from pathlib import Path
from typing import Any

import torch

from .checkpoint import load_actor
INPUT_NAME, OUTPUT_NAME = "obs", "action"


def _task_names(skill: str, spec: str) -> tuple[tuple[str, ...] | None, tuple[str, ...] | None]:
    """(feature names, action names) of a registered skill's task under the action
    mapping of ``spec``, or (None, None)."""
    from .registry import get_skill

    try:
        task = get_skill(skill).task
    except ValueError:
        return None, None
    if task is None:
        return None, None
    try:
        return task.names_of(task.mapping_of(spec))
    except ValueError:  # a spec the task does not list: its default names
        return tuple(task.feature_names), tuple(task.action_names)


def action_form_of(spec: str) -> dict[str, Any]:
    """How a network of observation spec ``spec`` acts: ``{"kind": "direct"}`` (its output is
    the task action), or the residual / aim form a deployment must rebuild around it (the
    hand-coded controller, the combination rule with its scale, the press gate), read from
    the constants the skills themselves use."""
    from .passing_features import (RECEIVE_PRESS_RULE, RECEIVE_RESIDUAL_SCALE, RECEIVE_SPEC_PRESSED,
                                   RECEIVE_SPEC_RESIDUAL)
    from .redirect import REDIRECT_AIM_POST_MARGIN, REDIRECT_RESIDUAL_SCALE, REDIRECT_SPEC_AIM, REDIRECT_SPEC_RESIDUAL

    def residual(base: str, scale: float) -> dict[str, Any]:
        return {"kind": "residual", "base": base, "scale": scale,
                "combine": f"action = clip(base + {scale} * clip(output, -1, 1), -1, 1), per column",
                "note": "base is the hand-coded controller's (vx, vy, omega) in the same state and frame; "
                        "an output of 0 is the hand-coded controller"}

    receive = residual("ssl_marl.skills.passing.ReceiveBaseline (the hand-coded receive)", RECEIVE_RESIDUAL_SCALE)
    if spec == RECEIVE_SPEC_RESIDUAL:
        return receive
    if spec == RECEIVE_SPEC_PRESSED:
        return {**receive,
                "gate": {"rule": RECEIVE_PRESS_RULE, "names": "the input columns of ssl_marl.obs_names",
                         "outside": "the base action alone (the network is not run)",
                         "function": "ssl_marl.skills.passing_features.receive_press_active"}}
    if spec == REDIRECT_SPEC_RESIDUAL:
        return residual("ssl_marl.skills.redirect.RedirectBaseline (the hand-coded redirect)",
                        REDIRECT_RESIDUAL_SCALE)
    if spec == REDIRECT_SPEC_AIM:
        return {"kind": "aim", "base": "ssl_marl.skills.redirect.RedirectBaseline's contact planner",
                "combine": f"output[0] in [-1, 1] is the aim point's y along the goal mouth: -1 / +1 = "
                           f"{REDIRECT_AIM_POST_MARGIN} m inside the right / left post "
                           "(ssl_marl.skills.redirect.redirect_aim_point)"}
    return {"kind": "direct"}


def onnx_metadata(meta: dict[str, Any]) -> dict[str, str]:
    """The ``metadata_props`` (str -> str) written for a checkpoint's metadata."""
    skill = str(meta.get("skill"))
    obs_dim, act_dim = int(meta["obs_dim"]), int(meta["act_dim"])
    names, action_names = _task_names(skill, str(meta.get("obs_spec")))
    props = {
        "ssl_marl.skill": skill,
        "ssl_marl.obs_spec": str(meta.get("obs_spec")),
        "ssl_marl.obs_dim": str(obs_dim),
        "ssl_marl.act_dim": str(act_dim),
        "ssl_marl.obs_normalisation": json.dumps(
            {"kind": "none", "note": "features are fed raw in SI units (m, m/s, rad/s) and sin/cos; "
                                     "build them as ssl_marl.skills.features does for obs_spec"}),
        "ssl_marl.input": json.dumps({"name": INPUT_NAME, "shape": ["batch", obs_dim], "dtype": "float32"}),
        "ssl_marl.output": json.dumps({"name": OUTPUT_NAME, "shape": ["batch", act_dim], "dtype": "float32",
                                       "range": [-1.0, 1.0]}),
        "ssl_marl.action_form": json.dumps(action_form_of(str(meta.get("obs_spec")))),
        "ssl_marl.metadata": json.dumps(meta, sort_keys=True),
    }
    if names is not None and len(names) == obs_dim:
        props["ssl_marl.obs_names"] = json.dumps(list(names))
    if action_names is not None and len(action_names) == act_dim:
        props["ssl_marl.action_names"] = json.dumps(list(action_names))
    for key in ("action_low", "action_high"):
        if key in meta:
            props[f"ssl_marl.{key}"] = json.dumps(meta[key])
    return props


def export_onnx(checkpoint: str | os.PathLike, out: str | os.PathLike, opset: int = 17) -> dict[str, Any]:
    """Write the actor in ``checkpoint`` to ``out`` (ONNX, atomically); return the checkpoint metadata.

    Raises FileNotFoundError / ValueError for a missing or invalid checkpoint (as
    :func:`~ssl_marl.skills.checkpoint.load_actor`), RuntimeError if the ``onnx``
    extra is not installed.
    """
    try:
        import onnx
    except ImportError:
        raise RuntimeError("export-onnx needs the 'onnx' extra: pip install -e \".[onnx]\"") from None
    from ..io import atomic_write_bytes

    actor, meta = load_actor(checkpoint)
    example = torch.zeros(1, actor.obs_dim, dtype=torch.float32)
    buf = io.BytesIO()
    with torch.no_grad(), warnings.catch_warnings():
        # dynamo=False: the TorchScript exporter needs no extra package (the torch.export
        # one needs onnxscript) and is exact for this plain MLP; its deprecation notice is
        # for PyTorch developers, not for the user exporting a skill.
        warnings.simplefilter("ignore", DeprecationWarning)
        torch.onnx.export(actor, (example,), buf, input_names=[INPUT_NAME], output_names=[OUTPUT_NAME],
                          dynamic_axes={INPUT_NAME: {0: "batch"}, OUTPUT_NAME: {0: "batch"}},
                          opset_version=int(opset), dynamo=False)
    model = onnx.load_from_string(buf.getvalue())
    model.producer_name = "ssl_marl"
    model.doc_string = (f"ssl_marl learned skill {meta.get('skill')} ({meta.get('obs_spec')}): "
                        f"{INPUT_NAME} (batch, {actor.obs_dim}) -> {OUTPUT_NAME} (batch, {actor.act_dim}) in [-1, 1]")
    onnx.helper.set_model_props(model, onnx_metadata(meta))
    onnx.checker.check_model(model)
    atomic_write_bytes(Path(out), model.SerializeToString())
    return meta


def read_onnx_metadata(path: str | os.PathLike) -> dict[str, str]:
    """The ``metadata_props`` of an ONNX model file as a dict."""
    import onnx

    return {p.key: p.value for p in onnx.load(str(path)).metadata_props}
