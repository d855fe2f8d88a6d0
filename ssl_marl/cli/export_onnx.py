"""``ssl-marl export-onnx``: a learned-skill actor checkpoint as an ONNX model."""

from __future__ import annotations

import argparse
import sys

from .options import int_at_least


def register(subparsers: argparse._SubParsersAction) -> None:
    """Add the ``export-onnx`` subparser."""
    x = subparsers.add_parser("export-onnx", help="write a learned-skill actor checkpoint as an ONNX model",
                              description="Export a learned-skill actor (an ssl_marl actor checkpoint, e.g. "
                                          "ssl_marl/skills/pretrained/go_to_ball.pt or a run's actor.pt) to ONNX for "
                                          "deployment in C++/Rust (onnxruntime). Input 'obs' (batch, obs_dim) "
                                          "float32, output 'action' (batch, act_dim) in [-1, 1]; the observation "
                                          "spec, feature names, normalisation and action mapping are in the "
                                          "model's metadata_props. Needs the 'onnx' extra: pip install -e "
                                          "\".[onnx]\".")
    x.add_argument("checkpoint", help="actor checkpoint (.pt) written by ssl_marl (weights only; never executed)")
    x.add_argument("out", help="output .onnx path (missing folders are created)")
    x.add_argument("--opset", type=int_at_least("--opset", 13), default=17, help="ONNX opset version (default 17)")
    x.set_defaults(handler=run)


def run(args: argparse.Namespace) -> int:
    """Write a learned-skill actor checkpoint as an ONNX model (see :mod:`ssl_marl.skills.onnx_export`)."""
    import importlib.util

    from ..io import prepare_output_file

    missing = [m for m in ("onnx", "onnxruntime") if importlib.util.find_spec(m) is None]
    if missing:
        print(f"ssl-marl export-onnx: error: needs {' and '.join(missing)}: pip install -e \".[onnx]\"",
              file=sys.stderr)
        return 2
    from ..skills.onnx_export import export_onnx

    prepare_output_file(args.out, (".onnx",), "OUT")
    meta = export_onnx(args.checkpoint, args.out, opset=args.opset)
    print(f"{args.checkpoint} ({meta['skill']}, {meta['obs_spec']}, obs {meta['obs_dim']} -> act {meta['act_dim']})"
          f" -> {args.out}")
    return 0
