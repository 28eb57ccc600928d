"""Bad inputs the lead found beside the fifteenth hostile pass, one test per rule."""

import pytest

from tegrasp_drake import cli
from tests.test_bad_input import run_cli


# Rule: a command's optional positional may follow its options, as a required one may:
# `plot signals -vv LOG` reads LOG (argparse alone gave LOG|RESULTS its default when -vv came
# first, then refused LOG as an unrecognized argument).
@pytest.mark.parametrize("argv", [["plot", "trial", "-vv", "{log}", "--out", "{png}"],
                                  ["plot", "-v", "trial", "{log}", "--out", "{png}"],
                                  ["plot", "trial", "--out", "{png}", "-q", "{log}"]])
def test_an_optional_positional_after_an_option_is_taken(tmp_path, capfd, argv):
    log, png = tmp_path / "missing.npz", tmp_path / "x.png"
    code, error = run_cli([a.format(log=log, png=png) for a in argv], capfd)
    assert code == 1, error
    assert f"trial log '{log}' does not exist" in error
    assert "unrecognized arguments" not in error


def test_two_positionals_where_one_is_taken_are_still_refused(tmp_path, capfd):
    with pytest.raises(SystemExit) as exit_:
        cli.main(["plot", "trial", "-v", str(tmp_path / "a.npz"), str(tmp_path / "b.npz")])
    assert exit_.value.code == 2
    assert "unrecognized arguments" in capfd.readouterr().err
