from benchmarks.pad_contact_reads import format_report, main


def test_report_gives_each_part_and_the_difference():
    result = {"surfaces": [(388, 499, "triangle")], "repeats": 3,
              "median_us": {"per element/read": 1800.0, "bulk/read": 1000.0,
                            "per element/integral": 1000.0, "bulk/integral": 700.0,
                            "per element/sample": 3000.0, "bulk/sample": 1800.0},
              "ratio": {"read": 1000 / 1800, "integral": 0.7, "sample": 0.6},
              "max_force_n": 2.3, "max_relative_difference": 0.0}
    lines = format_report(result).splitlines()
    assert "388 faces, 499 vertices (triangle)" in lines[0]
    assert lines[3].split() == ["read", "1800", "1000", "0.56"]
    assert lines[5].split() == ["sample", "3000", "1800", "0.60"]
    assert "0.0e+00" in lines[-1]


def test_fewer_than_one_repeat_is_a_usage_error(capsys):
    import pytest
    with pytest.raises(SystemExit) as exit_info:
        main(["--repeats", "0"])
    assert exit_info.value.code == 2
    assert "--repeats 0" in capsys.readouterr().err
