"""The argument parser of every command line in the package (`tegrasp`, its subcommands and
the `python -m` docs commands): a command line that does not parse is refused in one line
(docs/user-guide.md, "Exit codes"), never argparse's usage block; an argument holding a
control character is a command line that does not parse (argument_text_problem)."""

import argparse
import os
import re

EXIT_USAGE = 2  # a command line that does not parse (argparse's own code)
EXIT_BAD_INPUT = 1  # a command line that parses, with a value that cannot be used

# Text starting with '-' that is read as a value, not an option: argparse's negative numbers
# (-1, -.5) and all other text that starts as a number does (-inf, -1@3, -1_0), so that
# `--attempts -inf` is refused by the option's own check naming the value, never as "expected
# one argument". An option the parser has (`--attempts --dry-run`, `-v`) is still an option.
VALUE_LIKE_A_NUMBER = re.compile(r"^-(?:\d|\.|inf|nan)", re.IGNORECASE)

# Every control character (C0, DEL, C1): in an argument, a line break would split the one-line
# error that echoes it, an escape drive the terminal, a NUL be refused deep in a check.
CONTROL_CHARACTER = re.compile("[\x00-\x1f\x7f-\x9f]")
_CONTROL_NAMES = {0x00: "NUL", 0x09: "tab", 0x0a: "line break", 0x0d: "carriage return",
                  0x1b: "escape", 0x7f: "DEL"}


def argument_text_problem(text: str) -> str | None:
    """Why `text`, a command-line argument, cannot be one, in words that follow "argument
    --out ": the first control character it holds, by its code and its byte (counted from
    1, as the shell's text is UTF-8), or None."""
    found = CONTROL_CHARACTER.search(text)
    if found is None:
        return None
    code = ord(found.group())
    byte = len(os.fsencode(text[:found.start()])) + 1
    name = f", {_CONTROL_NAMES[code]}" if code in _CONTROL_NAMES else ""
    return (f"holds a control character (0x{code:02x}{name}) at byte {byte}; command-line "
            "text takes printable characters only: remove it")


class UsageParser(argparse.ArgumentParser):
    """argparse's parser, ending a command line that does not parse with one line on stderr,
    `PROG: error: <what> (see PROG --help)`, the user's text quoted safely
    (files.error_line), and EXIT_USAGE. Text starting as a number does (VALUE_LIKE_A_NUMBER)
    is an option's value."""

    def __init__(self, *args, **keywords):
        super().__init__(*args, **keywords)
        self._negative_number_matcher = VALUE_LIKE_A_NUMBER
        self.register("action", None, _StoreOnce)
        self.register("action", "store", _StoreOnce)

    def parse_known_args(self, args=None, namespace=None):
        """argparse's parse_known_args, a text default of this parser's arguments that holds
        a control character (one from the environment: LCM_DEFAULT_URL) refused as bad input
        (text_argument_problem); the command line's own text is refused by _get_values."""
        self._given_options = {}  # _StoreOnce's record of this parse's options
        parsed, extras = super().parse_known_args(args, namespace)
        problem = text_argument_problem(self, parsed)
        if problem:
            self.refuse(problem)
        return parsed, extras

    def error_lead(self) -> str:
        """How this parser's error lines start: `PROG: error: `."""
        return f"{self.prog}: error: "

    def refuse(self, message):
        """Ends a command line that parses, whose value `message` says cannot be used: one
        line on stderr and EXIT_BAD_INPUT."""
        self.exit(EXIT_BAD_INPUT, f"{self.error_lead()}{message}\n")

    def _get_values(self, action, arg_strings):
        """argparse's values of `action` from its arguments' text, an argument holding a
        control character refused first (argument_text_problem), each where the parser it
        belongs to takes it: a subcommand's name here, its arguments by its own parser."""
        given = arg_strings[:1] if action.nargs == argparse.PARSER else arg_strings
        for text in given:
            problem = argument_text_problem(text) if isinstance(text, str) else None
            if problem:
                from tegrasp_drake.rig.echo import shown
                name = argparse._get_action_name(action)  # as argparse's own errors name it
                self.error(f"argument {name} {problem}, got {shown(text)}")
        return super()._get_values(action, arg_strings)

    def error(self, message):
        from tegrasp_drake.rig.files import error_line
        self.exit(EXIT_USAGE, f"{self.error_lead()}{error_line(message)} "
                              f"(see {self.prog} --help)\n")


def text_argument_problem(parser: argparse.ArgumentParser, namespace) -> str | None:
    """The first of `parser`'s arguments in `namespace` whose text (a value, or one of a
    repeated option's) holds a control character (typed_yaml.text_problem: an escape would
    drive the terminal the value is echoed on, a NUL is refused deep in a check), named as
    the user wrote it, or None. An argument whose default may come from elsewhere (an
    environment variable) says where, by its `default_origin(value, name)` (e.g.
    hardware.config.lcm_url_origin), as its other checks do."""
    from tegrasp_drake.rig.echo import shorten
    from tegrasp_drake.rig.typed_yaml import text_problem
    for action in parser._actions:
        values = getattr(namespace, action.dest, None)
        for value in values if isinstance(values, (list, tuple)) else [values]:
            text = os.fspath(value) if isinstance(value, (str, os.PathLike)) else None
            problem = text_problem(text) if isinstance(text, str) else None
            if problem:
                name = (action.option_strings[0] if action.option_strings
                        else action.metavar or action.dest)
                origin = getattr(action, "default_origin", None)  # where a default came from
                name = origin(text, name) if origin is not None else name
                return f"{name} {problem}, got {shorten(repr(text))}"
    return None


class _StoreOnce(argparse._StoreAction):
    """argparse's `store`, refusing an option given again with another value: of
    `--out a --out b`, neither silently wins (a YAML file's repeated key is refused alike)."""

    def __call__(self, parser, namespace, values, option_string=None):
        # UsageParser empties the record at each parse; a parser of another class that
        # registered this action gets one here, kept across its parses
        seen = parser.__dict__.setdefault("_given_options", {})
        if self.dest in seen and seen[self.dest][1] != values:
            from tegrasp_drake.rig.echo import shown
            first, value = seen[self.dest]
            parser.error(f"{first} given twice ({shown(value)}, then {shown(values)}); give "
                         "it once")
        seen[self.dest] = (option_string or self.metavar or self.dest, values)
        super().__call__(parser, namespace, values, option_string)


class AppendSettings(argparse._AppendAction):
    """argparse's `append` for KEY=VALUE settings (--set, --config-set), refusing one key
    set twice to different values: neither silently wins. A class, not a registered name,
    so that a subcommand registered under any parser (argparse's own) has it."""

    def __call__(self, parser, namespace, values, option_string=None):
        from tegrasp_drake.rig.typed_yaml import key_set_twice, set_twice_words
        given = [*(getattr(namespace, self.dest, None) or ()), values]
        twice = key_set_twice(given)
        if twice:
            parser.error(f"{option_string} {set_twice_words(given, twice)}")
        super().__call__(parser, namespace, values, option_string)
