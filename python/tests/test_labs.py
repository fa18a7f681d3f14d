"""The labs' answer keys (docs/labs/*.answers.json) hold: every command each key lists is run
through the program and every answer compared (scripts/lab_answers.py, the script that writes
them), and each lab's page shows the commands its key runs."""
import glob
import importlib.util
import json
import os
import shlex

BINARY = os.environ.get("LIGHTCONE_BINARY", "build/lightcone")
SOURCE = os.environ.get("LIGHTCONE_SOURCE_DIR", ".")


def lab_answers():
    spec = importlib.util.spec_from_file_location(
        "lab_answers", os.path.join(SOURCE, "scripts", "lab_answers.py"))
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


def keys():
    return sorted(glob.glob(os.path.join(SOURCE, "docs", "labs", "*.answers.json")))


def test_every_answer_is_what_the_program_gives():
    assert len(keys()) >= 4
    assert lab_answers().check(os.path.abspath(BINARY)) == []


def test_a_changed_answer_is_caught(tmp_path, monkeypatch):
    # The check can fail: one key with one answer off in its seventh digit.
    module = lab_answers()
    entries = json.load(open(keys()[0]))
    entries[0]["value"] *= 1 + 1e-7
    changed = tmp_path / "changed.answers.json"
    changed.write_text(json.dumps(entries))
    monkeypatch.setattr(module, "KEYS", str(changed))
    problems = module.check(os.path.abspath(BINARY))
    assert len(problems) == 1 and entries[0]["question"] in problems[0]


def test_each_page_shows_the_commands_its_key_runs():
    for key in keys():
        page = open(key.replace(".answers.json", ".md")).read()
        flat = " ".join(page.replace("\\\n", " ").split())
        for entry in json.load(open(key)):
            words = shlex.split(entry["command"])
            assert " ".join(words) in flat, (key, entry["command"])
