"""The full references of the papers whose equation numbers zwidth shows: ONE definition.

Every place that names an equation, section or figure number of a paper (the app's tabs, the
report, the documentation) cites the paper in full from here:

* :data:`ADAMS` -- Adams, Moreyra & Hannaford (1998): the device chain (eq. 25-28), the two-port
  design of the impedance display (eq. 1-12) and of the admittance display (eq. 13-24, 30), the
  HBFD example (sections V-VI);
* :data:`EOM` -- Eom, Suh & Yi (2000): the virtual wall's transparency index (eq. 7-12), its
  robust stability (eq. 13-17) and the disturbance observer (eq. 2-5);
* :data:`COLGATE_BROWN`, :data:`COLGATE_SCHENKEL`, :data:`CHAWDA`, :data:`HANNAFORD_RYU`,
  :data:`MOREYRA_HANNAFORD` -- the (B, K) Z-width region, the passivity limit of a sampled wall,
  the optimum velocity-filter cut-off, time-domain passivity control, and the measurement of the
  HBFD model.

A :class:`Reference` renders as plain text (:meth:`Reference.text`, for the GUI), HTML
(:meth:`Reference.html`, for the report) or Markdown/reStructuredText (:meth:`Reference.markup`,
title in ``*italics*``).  Plain data, no numerics; never imports Qt.
"""

from __future__ import annotations

import html as _html
from dataclasses import dataclass

__all__ = [
    "ADAMS",
    "CHAWDA",
    "COLGATE_BROWN",
    "COLGATE_SCHENKEL",
    "COLONNESE_CHAN",
    "COLONNESE_OKAMURA",
    "LI_TAVAKOLI_HUANG",
    "CAVUSOGLU",
    "EOM",
    "HANNAFORD_RYU",
    "MOREYRA_HANNAFORD",
    "REFERENCES",
    "Reference",
    "citation_text",
]


@dataclass(frozen=True)
class Reference:
    """One paper: ``short`` is how the program names it ("Adams, Moreyra & Hannaford").

    Attributes
    ----------
    short : str
        How the program names the paper, e.g. ``"Adams, Moreyra & Hannaford"``.
    authors : str
        The authors as cited, e.g. ``"Adams, R. J., Moreyra, M. R., & Hannaford, B."``.
    year : int
        Year of publication.
    title : str
        Title of the paper.
    venue : str
        Where it appeared (proceedings or journal, volume, pages).
    """

    short: str
    authors: str
    year: int
    title: str
    venue: str

    def text(self) -> str:
        """Plain full citation: ``Authors (year). Title. Venue.``

        Returns
        -------
        str
            The citation as plain text.
        """
        return f"{self.authors} ({self.year}). {self.title}. {self.venue}."

    def markup(self) -> str:
        """The citation with the title in ``*italics*`` (Markdown and reStructuredText).

        Returns
        -------
        str
            The citation as markup.
        """
        return f"{self.authors} ({self.year}). *{self.title}*. {self.venue}."

    def html(self) -> str:
        """The citation as escaped HTML with the title in ``<i>``.

        Returns
        -------
        str
            The citation as HTML.
        """
        return (f"{_html.escape(self.authors)} ({self.year}). <i>{_html.escape(self.title)}</i>. "
                f"{_html.escape(self.venue)}.")


ADAMS = Reference(
    "Adams, Moreyra & Hannaford",
    "Adams, R. J., Moreyra, M. R., & Hannaford, B.",
    1998,
    "Stability and Performance of Haptic Displays: Theory and Experiments",
    "Proceedings of the ASME International Mechanical Engineering Congress and Exposition, Haptic "
    "Interfaces for Virtual Environment and Teleoperator Systems, DSC-Vol. 64, Anaheim, CA, pp. 227–234",
)
EOM = Reference(
    "Eom, Suh & Yi",
    "Eom, K. S., Suh, I. H., & Yi, B.-J.",
    2000,
    "A Design Method of Haptic Interface Controller Considering Transparency and Robust Stability",
    "Proceedings of the IEEE/RSJ International Conference on Intelligent Robots and Systems "
    "(IROS 2000), Takamatsu, Japan",
)
COLGATE_BROWN = Reference(
    "Colgate & Brown",
    "Colgate, J. E., & Brown, J. M.",
    1994,
    "Factors Affecting the Z-Width of a Haptic Display",
    "Proceedings of the IEEE International Conference on Robotics and Automation (ICRA 1994), "
    "pp. 3205–3210",
)
COLGATE_SCHENKEL = Reference(
    "Colgate & Schenkel",
    "Colgate, J. E., & Schenkel, G. G.",
    1997,
    "Passivity of a Class of Sampled-Data Systems: Application to Haptic Interfaces",
    "Journal of Robotic Systems, 14(1), pp. 37–47",
)
CHAWDA = Reference(
    "Chawda, Celik & O'Malley",
    "Chawda, V., Celik, O., & O'Malley, M. K.",
    2015,
    "A Method for Selecting Velocity Filter Cut-Off Frequency for Maximizing Impedance Width "
    "Performance in Haptic Interfaces",
    "ASME Journal of Dynamic Systems, Measurement, and Control, 137(2), 024503, "
    "doi:10.1115/1.4028526",
)
HANNAFORD_RYU = Reference(
    "Hannaford & Ryu",
    "Hannaford, B., & Ryu, J.-H.",
    2002,
    "Time-Domain Passivity Control of Haptic Interfaces",
    "IEEE Transactions on Robotics and Automation, 18(1), pp. 1–10",
)
MOREYRA_HANNAFORD = Reference(
    "Moreyra & Hannaford",
    "Moreyra, M. R., & Hannaford, B.",
    1998,
    "A Practical Measure of Dynamic Response of Haptic Devices",
    "Proceedings of the IEEE International Conference on Robotics and Automation (ICRA 1998), "
    "Leuven, Belgium, pp. 369–374",
)
COLONNESE_OKAMURA = Reference(
    "Colonnese & Okamura",
    "Colonnese, N., & Okamura, A. M.",
    2012,
    "M-Width: Stability and Accuracy of Haptic Rendering of Virtual Mass",
    "Robotics: Science and Systems VIII (RSS 2012), Sydney, Australia",
)
COLONNESE_CHAN = Reference(
    "Colonnese & Chan",
    "Colonnese, N., & Chan, S.",
    2016,
    "Z-Qualities and Renderable Mass-Damping-Stiffness Spaces: Describing the Set of Renderable "
    "Dynamics of Kinesthetic Haptic Displays",
    "Proceedings of the IEEE Haptics Symposium (HAPTICS 2016)",
)
LI_TAVAKOLI_HUANG = Reference(
    "Li, Tavakoli & Huang",
    "Li, J., Tavakoli, M., & Huang, Q.",
    2014,
    "Absolute Stability of Multi-DOF Multilateral Haptic Systems",
    "IEEE Transactions on Control Systems Technology, doi:10.1109/TCST.2014.2301840",
)
CAVUSOGLU = Reference(
    "Çavuşoğlu, Feygin & Tendick",
    "Çavuşoğlu, M. C., Feygin, D., & Tendick, F.",
    2002,
    "A Critical Study of the Mechanical and Electrical Properties of the PHANToM Haptic Interface "
    "and Improvements for High-Performance Control",
    "Presence: Teleoperators and Virtual Environments, 11(6)",
)

REFERENCES: tuple[Reference, ...] = (ADAMS, EOM, COLGATE_BROWN, COLGATE_SCHENKEL, CHAWDA,
                                     HANNAFORD_RYU, MOREYRA_HANNAFORD, COLONNESE_OKAMURA, COLONNESE_CHAN,
                                     LI_TAVAKOLI_HUANG, CAVUSOGLU)


def citation_text(primary: Reference, *others: Reference) -> str:
    """The note of a page whose equation numbers refer to ``primary`` and that also names ``others``.

    One paragraph, "Equation numbers refer to <full citation>. Also cited: <full citation>
    <full citation>".

    Parameters
    ----------
    primary : Reference
        The paper whose equation numbers the page shows.
    *others : Reference
        Other papers the page cites.

    Returns
    -------
    str
        The note, in plain text.
    """
    text = f"Equation numbers refer to {primary.text()}"
    if others:
        text += " Also cited: " + " ".join(r.text() for r in others)
    return text
