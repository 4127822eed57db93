"""The papers the known thread modules come from, named as a reader would cite them.

Hovers and messages name a paper by its author and title (and journal, where the copy we have
names it), never by the project's file numbers.
"""

from __future__ import annotations

from dataclasses import dataclass

from ..translation import tr

# The page that cites each paper in full, under a heading of its own (``Paper.anchor``).
PAPERS_URL = "https://github.com/fanuc-macro/fanuc-macro/blob/main/docs/papers.md"


@dataclass(frozen=True)
class Paper:
    authors: str
    title: str  # as published
    gloss: str = ""  # the title in English, where it was published in Chinese
    journal: str = ""  # empty: not named in the copy the project has
    anchor: str = ""  # the heading of docs/papers.md that cites it

    @property
    def authors_short(self) -> str:
        """``Deng Ronggang``, ``Ren Guozhu et al.``: a short link's text."""
        first = self.authors.split(" (")[0].split(",")[0]
        return first + (" et al." if "," in self.authors else "")

    @property
    def link(self) -> str:
        """Where the paper is cited in full."""
        return f"{PAPERS_URL}#{self.anchor}"

    @property
    def by(self) -> str:
        """``Deng Ronggang's paper``: for a message, where the title would be too long."""
        return tr("{authors}'s paper", authors=self.authors_short)

    @property
    def short(self) -> str:
        """``Deng Ronggang (邓荣刚), 《宏指令在钼电极加工中的应用》``: for a hover."""
        title = f"《{self.title}》" if self.gloss else self.title
        return f"{self.authors}, {title}"

    @property
    def citation(self) -> str:
        return f"{self.short}, {self.journal}" if self.journal else self.short


# The symmetric ("left-right") thread module O3331 / O3330 with its main programs O4009 / O4010,
# parameter tables 2 and 3, example M50x3 (table 4). The copy names no journal.
DENG_MOLYBDENUM = Paper(
    "Deng Ronggang (邓荣刚)",
    "宏指令在钼电极加工中的应用",
    "Macro programs in molybdenum electrode machining",
    anchor="deng-ronggang",
)
# The fitting-method arc thread macros O1-O5. Journal from the copy's DOI
# 10.3969/j.issn.1000-7008.2021.10.013 (ISSN 1000-7008 is 工具技术; unverified beyond the DOI).
REN_ARC_THREAD = Paper(
    "Ren Guozhu (任国柱), Qi Houjun (戚厚军), Wang Zhe (王喆)",
    "基于宏程序的大螺距圆弧螺纹加工方法探讨",
    "Machining large-pitch arc threads with macro programs",
    "工具技术 (Tool Engineering) 2021, no. 10",
    anchor="ren-guozhu-qi-houjun-wang-zhe",
)
# The drum-shaped spiral groove cut as chained taper threads (main program O0010).
PU_DRUM_GROOVE = Paper(
    "Pu Yanmin",
    "The application of macro program in drum-shaped spiral groove manufacturing",
    anchor="pu-yanmin",
)
