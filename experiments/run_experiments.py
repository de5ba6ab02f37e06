#!/usr/bin/python3
"""Reproduces the paper's experiments as a report: DIR/report.md, DIR/report.html, DIR/data/*.json|csv.

    /usr/bin/python3 experiments/run_experiments.py --out out/report          # full report (< 10 min, 2 cores)
    /usr/bin/python3 experiments/run_experiments.py --out out/quick --quick  # reduced (bundled/generated meshes)
"""
from __future__ import annotations

import argparse
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))

from iarap_experiments.cli import Cli, find_cli  # noqa: E402
from iarap_experiments.context import Context  # noqa: E402
from iarap_experiments.report import build_report  # noqa: E402

REPO = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--out", required=True, help="report folder (created)")
    parser.add_argument("--quick", action="store_true",
                        help="reduced report: small bundled/generated meshes, few iterations")
    parser.add_argument("--cli", default=None, help="iarap binary (default: $IARAP_CLI, else build/iarap)")
    parser.add_argument("--meshes", default=os.path.join(REPO, "..", "shared", "meshes"),
                        help="folder of the shared test meshes (default ../shared/meshes; skipped when absent)")
    parser.add_argument("--threads", type=int, default=os.cpu_count() or 1,
                        help="thread count of the 'all cores' timings (default: all hardware threads)")
    args = parser.parse_args()
    cli = Cli(os.path.abspath(args.cli or find_cli(REPO)))
    if not os.access(cli.path, os.X_OK):
        parser.error(f"{cli.path}: no iarap binary there (build it with `bash scripts/build.sh`)")
    shared = os.path.abspath(args.meshes) if os.path.isdir(args.meshes) and not args.quick else None
    os.makedirs(args.out, exist_ok=True)
    ctx = Context(cli=cli, repo=REPO, out=os.path.abspath(args.out), quick=args.quick, shared_meshes=shared,
                  threads_all=args.threads)
    failures = build_report(ctx)
    print(f"experiments: wrote {os.path.join(args.out, 'report.md')} and report.html"
          + (f" ({failures} section(s) failed, see the report)" if failures else ""), file=sys.stderr)
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
