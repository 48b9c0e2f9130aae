#!/usr/bin/python3
"""The starter Grafana dashboard (docs/grafana/aperture.json) against the server's metrics.

  * the file is valid JSON (what `python3 -m json.tool` checks) with a title, a uid and panels;
  * every panel has a query, and every aperture_* metric a query names is one aperture-server
    exports (server/service_metrics.cc; a histogram's _bucket, _sum and _count series by their
    family), so the dashboard cannot drift from the metrics;
  * every metric family the server exports is shown by some panel.

usage: grafana_dashboard_test.py --repo ROOT
"""

import argparse
import json
import re
import sys


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("--repo", required=True)
    args = parser.parse_args()
    path = f"{args.repo}/docs/grafana/aperture.json"
    errors = []
    try:
        with open(path, encoding="utf-8") as f:
            dashboard = json.load(f)
    except (OSError, ValueError) as e:
        print(f"FAIL: {path}: {e}")
        return 1
    for key in ("title", "uid", "panels"):
        if not dashboard.get(key):
            errors.append(f"the dashboard has no {key}")

    with open(f"{args.repo}/server/service_metrics.cc", encoding="utf-8") as f:
        exported = set(re.findall(r'"(aperture_[a-z_]+)"', f.read()))
    if len(exported) < 10:
        errors.append(f"found only {sorted(exported)} in server/service_metrics.cc")

    shown = set()
    for panel in dashboard.get("panels", []):
        targets = panel.get("targets") or []
        if not targets:
            errors.append(f"panel '{panel.get('title')}' has no query")
        for target in targets:
            for name in re.findall(r"\b(aperture_[a-z_]+)", target.get("expr", "")):
                family = re.sub(r"_(bucket|sum|count)$", "", name)
                if family not in exported:
                    errors.append(f"panel '{panel.get('title')}' queries {name}, which "
                                  "aperture-server does not export")
                shown.add(family)
    for name in sorted(exported - shown):
        errors.append(f"no panel shows {name}")

    for e in errors:
        print(f"FAIL: {e}")
    if errors:
        return 1
    print(f"grafana dashboard: valid JSON, {len(dashboard['panels'])} panels, "
          f"{len(shown)} metric families, all exported by aperture-server")
    return 0


if __name__ == "__main__":
    sys.exit(main())
