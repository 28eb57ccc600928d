"""The docs' rule tables as Markdown, generated from each registered controller's RuleTable
(`python -m tegrasp_drake.control.rule_docs [--write|--check docs/controller.md]`). A table
lies between `<!-- rule table: NAME -->` (`NAME, added`: only what NAME adds) and
`<!-- end of rule table -->`; --write replaces it atomically."""

import pathlib
import re
import sys

from tegrasp_drake.control.controller_registry import rule_tables
from tegrasp_drake.control.rule_engine import LIVE_MODES, RuleTable
from tegrasp_drake.rig.usage_parser import UsageParser

BEGIN = re.compile(r"^<!-- rule table: (?P<name>\w+)(?P<added>, added)? -->$", re.MULTILINE)
END = "<!-- end of rule table -->"


def _rows(table: RuleTable, added_only: bool) -> list[tuple[str, object]]:
    """(mode label, rule) in the docs' order: all modes' rules first, then by mode and priority."""
    def shown(rule) -> bool:
        return not added_only or table.origin(rule.name) == table.name
    rows = [("any", rule) for rule in sorted(table.all_rules(), key=lambda r: r.priority)
            if rule.modes is None and shown(rule)]
    for mode in LIVE_MODES:
        rows += [(mode.label, rule) for rule, _ in table.ordered(mode)
                 if rule.modes is not None and shown(rule)]
    return rows


def hands_label(item) -> str:
    """A rule's or guard's hands for the docs: "both" (every hand model), or their names."""
    return "both" if item.hands is None else ", ".join(item.hands)


def markdown(table: RuleTable, *, added_only: bool = False) -> str:
    """The table's rules, then its guards, as Markdown (`from`, `hands` and `held back by`
    columns when it has a base, a rule or guard kept to some hands, or guards); `added_only`:
    only what it adds to its base."""
    move = table.re_reach_move
    guards = table.all_guards() if not added_only else table.guards
    held = {rule.name: [g.name for g in table.all_guards() if rule.name in g.holds_back]
            for rule in table.all_rules()}
    kept = any(item.hands is not None for item in (*table.all_rules(), *table.all_guards()))
    # The columns "from" for an extended table, "hands" for one with a rule or guard kept to
    # some hands, "held back by" for one with guards.
    columns = ["mode", "priority", "rule"] + ["from"] * (table.base is not None) + [
        "hands"] * kept + ["held back by"] * bool(table.all_guards()) + ["when", "then"]
    lines = ["| " + " | ".join(columns) + " |", "|" + "---|" * len(columns)]
    for mode, rule in _rows(table, added_only):
        cells = {"mode": mode, "priority": str(rule.priority), "rule": f"`{rule.name}`",
                 "from": table.origin(rule.name), "hands": hands_label(rule),
                 "held back by": ", ".join(f"`{g}`" for g in held[rule.name]) or "-",
                 "when": rule.when,
                 "then": rule.then.format(re_reach=move.label, re_reach_shift=move.shift_label)}
        lines.append("| " + " | ".join(cells[column] for column in columns) + " |")
    if guards:
        columns = ["guard", "from"] + ["hands"] * kept + ["holds back", "while"]
        lines += ["", "| " + " | ".join(columns) + " |", "|" + "---|" * len(columns)]
        for g in guards:
            cells = {"guard": f"`{g.name}`", "from": table.origin(g.name),
                     "hands": hands_label(g),
                     "holds back": ", ".join(f"`{name}`" for name in g.holds_back),
                     "while": g.when}
            lines.append("| " + " | ".join(cells[column] for column in columns) + " |")
    return "\n".join(lines) + "\n"


def updated_page(page: str, tables: dict[str, RuleTable]) -> tuple[str, list[str]]:
    """`page` with every rule table between its markers generated anew, and the names of
    the tables it holds. ValueError for a table the registry lacks or a missing end."""
    out, position, names = [], 0, []
    for begin in BEGIN.finditer(page):
        name = begin["name"]
        if name not in tables:
            raise ValueError(f"the page shows a rule table '{name}'; the controllers' tables "
                             f"are {', '.join(tables)}")
        end = page.find(END, begin.end())
        if end < 0:
            raise ValueError(f"the rule table '{name}' has no '{END}' line after it")
        out += [page[position:begin.end()], "\n",
                markdown(tables[name], added_only=bool(begin["added"]))]
        position, names = end, names + [name]
    return "".join(out) + page[position:], names


def main(argv=None) -> int:
    parser = UsageParser(prog="python -m tegrasp_drake.control.rule_docs",
                         description="The controllers' rule tables as Markdown.")
    action = parser.add_mutually_exclusive_group()
    action.add_argument("--write", type=pathlib.Path, metavar="PAGE",
                        help="regenerate the tables between their markers in PAGE")
    action.add_argument("--check", type=pathlib.Path, metavar="PAGE",
                        help="exit 1 when PAGE's tables differ from the engine's")
    args = parser.parse_args(argv)
    tables = rule_tables()
    path = args.write or args.check
    if path is None:
        for name, table in tables.items():
            print(f"{name}:\n\n{markdown(table)}")
        return 0
    try:
        page = path.read_text()
        updated, names = updated_page(page, tables)
    except (OSError, ValueError) as error:
        raise SystemExit(f"rule_docs: {path}: {error}") from None
    if args.check:
        if updated != page:
            print(f"{path}: its rule tables differ from the engine's; run `python -m "
                  f"tegrasp_drake.control.rule_docs --write {path}`")
            return 1
        print(f"{path}: the rule tables {', '.join(names)} agree with the engine")
        return 0
    from tegrasp_drake.rig.files import MARKDOWN_START, write_atomically
    write_atomically(path, updated, start=MARKDOWN_START)
    print(f"{path}: wrote the rule tables {', '.join(names)}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
