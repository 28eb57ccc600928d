"""Every error line of `tegrasp` starts with the one ERROR_LEAD (commands/error_boundary.py):
the package spells the lead in that one place, so a change to it reaches every command."""

import pathlib

from tegrasp_drake.commands.error_boundary import ERROR_LEAD

PACKAGE = pathlib.Path(__file__).resolve().parents[2] / "tegrasp_drake"


def test_the_error_lead_is_written_out_only_where_it_is_defined():
    definition = PACKAGE / "commands" / "error_boundary.py"
    literals = [f"{path.relative_to(PACKAGE)}:{number}"
                for path in sorted(PACKAGE.rglob("*.py")) if path != definition
                for number, line in enumerate(path.read_text(encoding="utf-8").splitlines(), 1)
                if f'"{ERROR_LEAD}' in line or f"'{ERROR_LEAD}" in line]
    assert literals == []
