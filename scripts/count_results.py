#!/usr/bin/env python3
"""Counts test cases in the JUnit/gtest XML files under a folder and prints
"N passed, N failed" (", N skipped" when any were). Counts <testcase> elements,
because catkin_test_results adds a gtest file's <testsuites> total to its
<testsuite> totals and so counts every gtest case twice. Exit 1 if any failed or
a file cannot be read."""
import sys
import xml.etree.ElementTree as ElementTree
from pathlib import Path


def main(folder):
    passed = failed = skipped = 0
    broken_files = []
    for path in sorted(Path(folder).rglob("*.xml")):
        try:
            root = ElementTree.parse(path).getroot()
        except ElementTree.ParseError:
            broken_files.append(path)
            continue
        for case in root.iter("testcase"):
            if case.find("failure") is not None or case.find("error") is not None:
                failed += 1
                print(f"FAILED: {path.name}: {case.get('classname')}.{case.get('name')}")
            elif case.find("skipped") is not None or case.get("status") == "notrun":
                skipped += 1
            else:
                passed += 1
    for path in broken_files:
        print(f"FAILED: unreadable result file {path}")
    failed += len(broken_files)
    line = f"{passed} passed, {failed} failed"
    if skipped:
        line += f", {skipped} skipped"
    print(line)
    return 1 if failed or passed == 0 else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1]))
