#!/usr/bin/env python3
"""The German and Romanian translations are complete and consistent with the sources.

Usage: translations_test.py LUPDATE SOURCE_LIST TS_FILE... [-- LUPDATE_OPTION...]

Each .ts file is copied and brought up to date with the sources by lupdate (the options the
build's update_translations target uses), so a tr() string added to the code without a
translation fails here, not only once someone runs update_translations. Then every message must
be translated (no type="unfinished", no empty text or numerus form), keep the placeholders (%1,
%n), the leading and trailing spaces (suffixes such as " px") and the keyboard mnemonic (&) of
its source, and the committed file must hold exactly the strings the sources have.
"""
import re
import shutil
import subprocess
import sys
import tempfile
import xml.etree.ElementTree as ET
from pathlib import Path

PLACEHOLDER = re.compile(r"%L?(?:\d+|n)")


def mnemonics(text):
    """How many keyboard mnemonics (a single &, not &&) the text has."""
    return len(re.findall(r"(?<!&)&(?!&)", text.replace("&&", "")))


def messages(ts_path):
    """(context, source) -> message element, for every message of a .ts file."""
    result = {}
    for context in ET.parse(ts_path).getroot().iter("context"):
        name = context.findtext("name")
        for message in context.iter("message"):
            result[(name, message.findtext("source"))] = message
    return result


def translation_problems(context, source, message):
    translation = message.find("translation")
    where = f"[{context}] {source!r}"
    if translation is None:
        return [f"{where}: no translation element"]
    kind = translation.get("type")
    if kind in ("unfinished", "obsolete", "vanished"):
        return [f"{where}: {kind}"]
    if message.get("numerus") == "yes":
        texts = [form.text or "" for form in translation.findall("numerusform")]
        if not texts:
            return [f"{where}: no numerus forms"]
    else:
        texts = [translation.text or ""]
    problems = []
    for text in texts:
        if not text.strip():
            problems.append(f"{where}: empty translation")
            continue
        if sorted(PLACEHOLDER.findall(source)) != sorted(PLACEHOLDER.findall(text)):
            problems.append(f"{where}: placeholders differ in {text!r}")
        if (source[: len(source) - len(source.lstrip())] != text[: len(text) - len(text.lstrip())]
                or source[len(source.rstrip()):] != text[len(text.rstrip()):]):
            problems.append(f"{where}: leading or trailing spaces differ in {text!r}")
        if mnemonics(source) != mnemonics(text):
            problems.append(f"{where}: the source has {mnemonics(source)} mnemonic(s) (&), "
                            f"{text!r} has {mnemonics(text)}")
    return problems


def check(lupdate, source_list, ts_path, options, work):
    problems = []
    language = ET.parse(ts_path).getroot().get("language", "")
    expected_language = ts_path.stem.rsplit("_", 1)[-1]
    if language.split("_")[0] != expected_language:
        problems.append(f'language="{language}", the file name says {expected_language}')

    updated = work / ts_path.name
    shutil.copyfile(ts_path, updated)
    run = subprocess.run([lupdate, f"@{source_list}", "-ts", str(updated), *options],
                         capture_output=True, text=True)
    if run.returncode != 0:
        return problems + [f"lupdate failed ({run.returncode}):\n{run.stdout}{run.stderr}"]

    committed = messages(ts_path)
    current = messages(updated)
    for context, source in sorted(current.keys() - committed.keys()):
        problems.append(f"[{context}] {source!r}: in the sources, not yet in the .ts file")
    for context, source in sorted(committed.keys() - current.keys()):
        problems.append(f"[{context}] {source!r}: in the .ts file, no longer in the sources")
    for (context, source), message in sorted(current.items()):
        if (context, source) in committed:
            problems += translation_problems(context, source, message)
    print(f"{ts_path.name}: {len(current)} strings, {len(problems)} problem(s)")
    return problems


def main(argv):
    options = []
    if "--" in argv:
        options = argv[argv.index("--") + 1:]
        argv = argv[: argv.index("--")]
    if len(argv) < 3:
        print(__doc__)
        return 2
    lupdate, source_list, ts_files = argv[0], argv[1], [Path(p) for p in argv[2:]]
    failed = False
    with tempfile.TemporaryDirectory() as work:
        for ts_path in ts_files:
            problems = check(lupdate, source_list, ts_path, options, Path(work))
            for problem in problems:
                print(f"FAIL {ts_path.name}: {problem}")
            failed |= bool(problems)
    if failed:
        print("Add new strings with `cmake --build BUILD --target update_translations`, then "
              "translate them (Qt Linguist) in translations/*.ts.")
        return 1
    print("PASS: every string is translated")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
