"""The one number formatter's three styles (issue 22): "ascii" for what scripts read, "text" for plain
text a person reads (a true minus "−" and a superscript power of ten), "rich" for Qt rich text / HTML;
the same digits in all three."""

from __future__ import annotations

import math
import re

import pytest

from analysis.study.quantities import (
    QUANTITIES,
    STYLES,
    ascii_numbers,
    format_number,
    rich_numbers,
    superscript_numbers,
)

#: an ASCII hyphen-minus directly before a digit (or a decimal point and a digit)
ASCII_MINUS = re.compile(r"-\.?\d")

VALUES = [-1e-5, -3.2, -0.000123456, -1.5e12, 2.5e-7, 123456789.0, -42.0, 0.0, 7.0]


@pytest.mark.parametrize("value", VALUES)
@pytest.mark.parametrize("digits", [2, 3, 4, 6])
def test_the_three_styles_print_the_same_digits(value, digits):
    plain = format_number(value, digits)
    text = format_number(value, digits, style="text")
    rich = format_number(value, digits, rich=True)
    assert plain == f"{value:.{digits}g}"  # the ASCII form is Python's g format, as before
    assert plain.isascii()
    assert ascii_numbers(text) == plain  # the display form reads back to exactly the ASCII digits
    assert float(ascii_numbers(text)) == float(plain)
    assert format_number(value, digits, style="rich") == rich
    assert not ASCII_MINUS.search(text) and "e" not in text
    assert not ASCII_MINUS.search(rich)
    assert ("−" in text) == (value < 0) == ("−" in rich.split("<sup>")[0])


def test_negative_numbers_and_exponents_are_typeset_in_the_text_style():
    assert format_number(-1e-5, style="text") == "−1×10⁻⁵"
    assert format_number(-1e-5) == "-1e-05"
    assert format_number(-1e-5, rich=True) == "−1×10<sup>−5</sup>"
    assert format_number(-3.2, style="text") == "−3.2"
    assert format_number(2.55e11, 3, style="text") == "2.55×10¹¹"
    assert format_number(-math.inf, style="text") == format_number(-math.inf, rich=True) == "−∞"
    assert format_number(-math.inf) == "-∞"
    # the words are the same in every style
    for style in STYLES:
        assert format_number(None, style=style) == "infeasible"
        assert format_number(math.nan, style=style) == "n/a"
        assert format_number(True, style=style) == "yes"
        assert format_number(math.inf, style=style) == "∞"


def test_scale_and_quantities_pass_the_style_through():
    reserve = QUANTITIES["stability_reserve"]  # a fraction printed in per cent, 4 digits
    assert reserve.format(-7.860944882779771) == "-786.1 %"
    assert reserve.format(-7.860944882779771, style="text") == "−786.1 %"
    assert reserve.parse(reserve.format(-7.860944882779771, style="text")) == pytest.approx(-7.861, abs=1e-12)
    b_min = QUANTITIES["b_min"]
    assert b_min.format(-1.0478e-9, style="text") == "−1.0478×10⁻⁹ N·s/m"
    assert b_min.parse(b_min.format(-1.0478e-9, style="text")) == -1.0478e-9
    assert b_min.parse("−∞") == -math.inf


def test_an_unknown_or_contradictory_style_is_refused():
    with pytest.raises(ValueError):
        format_number(1.0, style="latex")
    with pytest.raises(ValueError):
        format_number(1.0, rich=True, style="text")


def test_a_sentence_of_ascii_numbers_is_typeset_and_words_keep_their_hyphens():
    sentence = "no 2nd-order cut-off (eq. 10-11) beats it: -1.1 % at 3.804e+07, down to -4e-05 (-∞)"
    text = superscript_numbers(sentence)
    assert text == "no 2nd-order cut-off (eq. 10-11) beats it: −1.1 % at 3.804×10⁷, down to −4×10⁻⁵ (−∞)"
    assert rich_numbers(sentence) == ("no 2nd-order cut-off (eq. 10-11) beats it: −1.1 % at 3.804×10<sup>7</sup>, "
                                      "down to −4×10<sup>−5</sup> (−∞)")
    assert ascii_numbers(text) == sentence  # and back, for a CSV comment line
