"""Run every study: ``python studies/run_all.py [--fast] [--only NAME ...] [--out DIR]``.

Each ``studies/<name>.py`` that defines ``main(out_dir, fast)`` is imported and
run, writing into ``DIR/<name>/`` (default ``studies/out/<name>/``).  A study
that fails does not stop the others; the summary lists each with its time and
the exit status is 1 if any failed.  Studies that are not written yet are
simply absent (the index, ``studies/README.md``, lists them all).
"""

from __future__ import annotations

import argparse
import importlib.util
import sys
import time
import traceback
from pathlib import Path

HERE = Path(__file__).resolve().parent


def studies() -> dict[str, Path]:
    """name → path of every study script present (``studies/*.py`` other than this runner)."""
    return {p.stem: p for p in sorted(HERE.glob("*.py")) if p.stem != "run_all" and not p.stem.startswith("_")}


def load(name: str, path: Path):
    spec = importlib.util.spec_from_file_location(f"studies_{name}", path)
    mod = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(mod)
    return mod


def run(names=None, fast: bool = True, out: Path | None = None) -> dict[str, tuple[str, float]]:
    """Run the named studies (default: all); name → ("ok" | "FAILED: ..." | "no main()", seconds)."""
    found = studies()
    unknown = [n for n in names or [] if n not in found]
    if unknown:
        raise SystemExit(f"unknown studies: {', '.join(unknown)}; present: {', '.join(found)}")
    results = {}
    for name in names or found:
        t = time.perf_counter()
        try:
            mod = load(name, found[name])
            if not callable(getattr(mod, "main", None)):
                results[name] = ("no main(out_dir, fast)", 0.0)
                continue
            target = (out or HERE / "out") / name
            target.mkdir(parents=True, exist_ok=True)
            print(f"== {name} ({'fast' if fast else 'full'}) -> {target}", flush=True)
            mod.main(target, fast=fast)
            results[name] = ("ok", time.perf_counter() - t)
        except Exception as exc:  # one failing study must not hide the others
            traceback.print_exc()
            results[name] = (f"FAILED: {type(exc).__name__}: {exc}", time.perf_counter() - t)
    return results


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--fast", action="store_true", help="fast mode of every study (seconds each; CI)")
    parser.add_argument("--only", nargs="+", metavar="NAME", help="run only these studies")
    parser.add_argument("--out", type=Path, default=None, help="output root (default studies/out)")
    args = parser.parse_args(argv)
    results = run(args.only, args.fast, args.out)
    print("\nstudy                      time   status")
    for name, (status, secs) in results.items():
        print(f"{name:<24}{secs:>7.1f}s   {status}")
    return 1 if any(s.startswith("FAILED") for s, _ in results.values()) else 0


if __name__ == "__main__":
    sys.exit(main())
