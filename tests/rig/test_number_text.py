from tegrasp_drake.rig.number_text import count_text


def test_count_text_says_one_thing_in_the_singular_and_others_in_the_plural():
    assert count_text(1, "marker") == "1 marker"
    assert count_text(0, "marker") == "0 markers"
    assert count_text(4, "marker") == "4 markers"
