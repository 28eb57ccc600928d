"""Every `tegrasp ...` command that the README, the docs/ pages, the `--help` examples and the
package's own messages show exists: code-block lines and help examples parse with the real
parser, and every sub-command and `--option` named anywhere belongs to it. `--help` shows
examples."""

import argparse
import contextlib
import io
import pathlib
import re
import shlex

import pytest

from tegrasp_drake import cli

ROOT = pathlib.Path(__file__).resolve().parent.parent
README = ROOT / "README.md"
PACKAGE = ROOT / "tegrasp_drake"
# A synopsis or a sentence, not a command line: [optional], {choice}, a|b, "...".
SYNOPSIS = re.compile(r"\s\[|\{|\s\|\s|\.\.\.")


def subcommand_parsers() -> dict[str, argparse.ArgumentParser]:
    parser = cli.build_parser()
    action = next(a for a in parser._actions if isinstance(a, argparse._SubParsersAction))
    return dict(action.choices)


def code_block_commands(text: str) -> list[str]:
    """`tegrasp ...` lines of indented and fenced code blocks (after `&&`, before `&`/`#`)."""
    commands = []
    in_fence = False
    for line in text.splitlines():
        if line.startswith("```"):
            in_fence = not in_fence
            continue
        if not (in_fence or line.startswith("    ")):
            continue
        for part in line.split("&&"):
            part = part.split("#")[0].strip().rstrip("&").strip()
            if part.startswith("tegrasp "):
                commands.append(part)
    return commands


def inline_mentions(text: str) -> list[str]:
    """`tegrasp ...` spans in backticks."""
    return re.findall(r"`(tegrasp [^`]*)`", text)


def help_examples(parser) -> list[str]:
    return [line.split("#")[0].strip() for line in (parser.epilog or "").splitlines()
            if line.startswith("  tegrasp ")]


def parse(command: str):
    """Parses `command` with the real parser; -h/--help prints nothing and passes."""
    with contextlib.redirect_stdout(io.StringIO()), contextlib.redirect_stderr(io.StringIO()) \
            as errors:
        try:
            return cli.build_parser().parse_args(shlex.split(command)[1:])
        except SystemExit as e:
            assert e.code == 0, f"`{command}` does not parse: {errors.getvalue().strip()}"


def unknown_names(command: str, parsers) -> list[str]:
    """The sub-command and the --options of `command` that the real parser does not have."""
    words = command.split()
    name = words[1] if len(words) > 1 else ""
    if name.isupper() or not re.fullmatch(r"[a-z-]+", name):
        return []  # a placeholder (`tegrasp COMMAND --help`)
    if name.startswith("--"):  # an option of `tegrasp` itself (`tegrasp --version`)
        known = cli.build_parser()._option_string_actions
    elif name not in parsers:
        return [name]
    else:
        known = parsers[name]._option_string_actions
    options = re.findall(r"(?<![\w-])(--[a-z][a-z-]*)", command)
    return [option for option in options if option not in known]


def readme_text() -> str:
    return README.read_text(encoding="utf-8")


def page_texts() -> dict[str, str]:
    """The README and the docs/ pages by their path."""
    return {str(path.relative_to(ROOT)): path.read_text(encoding="utf-8")
            for path in [README, *sorted((ROOT / "docs").glob("*.md"))]}


def package_texts() -> dict[str, str]:
    return {str(path.relative_to(ROOT)): path.read_text(encoding="utf-8")
            for pattern in ("**/*.py", "**/*.md") for path in PACKAGE.glob(pattern)}


def test_readme_code_block_commands_parse():
    commands = code_block_commands(readme_text())
    assert "tegrasp demo" in commands  # the set-up command
    for command in commands:
        parse(command)


def test_docs_code_block_commands_parse():
    pages = page_texts()
    assert len(pages) > 1
    for text in pages.values():
        for command in code_block_commands(text):
            parse(command)


def test_every_documented_subcommand_and_option_exists():
    parsers = subcommand_parsers()
    sources = {**page_texts(), **package_texts()}
    problems = []
    for where, text in sources.items():
        for command in inline_mentions(text) + code_block_commands(text):
            for name in unknown_names(command, parsers):
                problems.append(f"{where}: `{command}`: no {name}")
    assert not problems, "\n".join(problems)


def test_the_checker_finds_a_stale_hint():
    # The hint this test was written for: `tegrasp demo` has no --log.
    assert unknown_names("tegrasp demo --log FILE", subcommand_parsers()) == ["--log"]
    assert unknown_names("tegrasp --versions", subcommand_parsers()) == ["--versions"]
    with pytest.raises(AssertionError, match="does not parse"):
        parse("tegrasp demo --log out/run.npz")


@pytest.mark.parametrize("name", sorted(subcommand_parsers()))
def test_help_shows_examples_that_parse(name):
    parser = subcommand_parsers()[name]
    assert "examples:" in parser.format_help()
    examples = help_examples(parser)
    assert examples and all(e.startswith(f"tegrasp {name}") for e in examples), examples
    for example in examples:
        if not SYNOPSIS.search(example):
            parse(example)


def test_demo_and_trial_help_differ_in_what_they_run_and_keep():
    parsers = subcommand_parsers()
    demo, trial = parsers["demo"].format_help(), parsers["trial"].format_help()
    assert demo != trial
    assert "out/demo" in demo and "replac" in demo
    assert "out/trial-2" in trial and "--overwrite" in trial
