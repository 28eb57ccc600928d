"""A docs page's table that code writes: the markdown between `<!-- MARKER -->` and
`<!-- end of MARKER -->`, checked against what the code computes and rewritten from it by a
module's `--check PAGE` / `--write PAGE` command (the docs show what the code holds, and a
test says so)."""

import dataclasses
import pathlib
import re
import sys
import typing

from tegrasp_drake.rig.usage_parser import UsageParser


@dataclasses.dataclass(frozen=True)
class GeneratedTable:
    """`name` says the table in messages ("the uncertain parameters table"); `marker` the
    comment that opens it; `markdown` computes it."""
    name: str
    marker: str
    markdown: typing.Callable[[], str]

    @property
    def begin(self) -> str:
        return f"<!-- {self.marker} -->\n"

    @property
    def end(self) -> str:
        return f"<!-- end of {self.marker} -->"

    def _block(self) -> re.Pattern:
        return re.compile(re.escape(self.begin) + r"(?P<table>.*?)" + re.escape(self.end),
                          re.DOTALL)

    def documented(self, text: str) -> str | None:
        """The table a page's text holds between the markers, or None when it has none."""
        match = self._block().search(text)
        return match["table"] if match else None

    def main(self, argv=None, *, description: str = "") -> int:
        """`--check PAGE` (exit 1 when the page's table is not the generated one) or `--write
        PAGE` (replace it); exit 2 when the page cannot be read or has no markers."""
        parser = UsageParser(description=description)
        group = parser.add_mutually_exclusive_group(required=True)
        group.add_argument("--check", metavar="PAGE")
        group.add_argument("--write", metavar="PAGE")
        args = parser.parse_args(argv)
        page = pathlib.Path(args.check or args.write)
        try:
            text = page.read_text(encoding="utf-8")
        except (OSError, UnicodeDecodeError) as error:
            print(f"{page}: cannot read it ({getattr(error, 'strerror', None) or error})",
                  file=sys.stderr)
            return 2
        if self.documented(text) is None:
            print(f"{page}: no '{self.begin.strip()}' ... '{self.end}' block", file=sys.stderr)
            return 2
        if args.check:
            same = self.documented(text) == self.markdown()
            print(f"{page}: {self.name} is "
                  + ("up to date" if same else "out of date: run with --write"))
            return 0 if same else 1
        from tegrasp_drake.rig.files import MARKDOWN_START, write_atomically
        write_atomically(page, self._block().sub(
            lambda m: self.begin + self.markdown() + self.end, text), start=MARKDOWN_START)
        print(f"wrote {self.name} into {page}")
        return 0
