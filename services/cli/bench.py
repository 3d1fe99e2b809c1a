"""``skydeck bench``: the benchmark suite, Skydeck against its references in one run.

The suite is the checkout's ``benchmarks`` package, beside ``services/``, not part of the product:
an installation without it (the Docker image) says so in one line.
"""

from __future__ import annotations

import argparse
import importlib.util
import sys
from pathlib import Path

from services.cli.arguments import positive_float, writable_file
from services.cli.errors import CliError

__all__ = ["add_parser"]

_DEFAULT_PLOTS = Path("docs/img")


def add_parser(subparsers: argparse._SubParsersAction[argparse.ArgumentParser]) -> None:
    p = subparsers.add_parser(
        "bench",
        help="measure topics, services, fan-out, the simulator, the AI's tours and startup against references",
        description=(
            "Runs each benchmark and its reference in the same run, interleaved and repeated, and prints a "
            "table of values, references and ratios (progress on stderr). See docs/performance.md."
        ),
    )
    p.add_argument("--quick", action="store_true", help="short run for CI: each family once (about 4 minutes on 2 cores)")
    p.add_argument("--out", type=writable_file, metavar="FILE.json", help="write the results as JSON")
    p.add_argument(
        "--plots",
        type=Path,
        metavar="DIR",
        help=f"write PNG plots there (default: {_DEFAULT_PLOTS} for a full run from the repository, none with --quick)",
    )
    p.add_argument("--no-plots", action="store_true", help="no plots, even for a full run")
    p.add_argument("--only", metavar="NAME[,NAME]", help="only the families of these rows (e.g. mission,service_rtt_p50)")
    p.add_argument(
        "--soak",
        type=positive_float,
        metavar="MINUTES",
        help="instead: run the drone world at --speed max with 50 viewers, a stalled reader and reconnecting "
        "clients for MINUTES, and report every process's memory (within 10%% of its value after warm-up)",
    )
    p.set_defaults(func=_bench)


def _bench(args: argparse.Namespace) -> int:
    if importlib.util.find_spec("benchmarks") is None:
        raise CliError(
            "skydeck bench runs the benchmark suite of a Skydeck checkout (benchmarks/ beside services/), "
            "which this installation does not have: run it from a checkout (`make bench`)"
        )
    if args.soak is not None:
        return _soak(args)
    from benchmarks import run_bench

    plots = args.plots
    if plots is None and not args.quick and not args.no_plots and _DEFAULT_PLOTS.is_dir():
        plots = _DEFAULT_PLOTS
    if args.no_plots:
        plots = None
    only = {name.strip() for name in args.only.split(",") if name.strip()} if args.only else None
    try:
        outcome = run_bench(quick=args.quick, out=args.out, plots=plots, only=only)
    except ValueError as error:
        raise CliError(str(error)) from None
    print(outcome.table)
    if args.out is not None:
        print(f"\nresults written to {args.out}", file=sys.stderr)
    for path in outcome.plots:
        print(f"plot written to {path}", file=sys.stderr)
    return 1 if outcome.errors else 0


def _soak(args: argparse.Namespace) -> int:
    from benchmarks.plots import write_plots
    from benchmarks.report import format_table, machine_info, write_json
    from benchmarks.soak import run_soak

    results, data = run_soak(args.soak)
    print(format_table(results))
    counters = data["counters"]
    print(
        f"load: {counters['frames']:,} pose frames to 50 viewers, {counters['reconnects']:,} reconnects, "
        f"{counters['stalled_readers']} stalled readers",
        file=sys.stderr,
    )
    if args.out is not None:
        write_json(args.out, results, machine_info(), {"soak_minutes": args.soak, **data})
    if args.plots is not None:
        for path in write_plots(data, args.plots):
            print(f"plot written to {path}", file=sys.stderr)
    return 0 if all(r.met for r in results) else 1
