"""The hands a taxel_aware rule or guard is kept to (Rule.hands, Guard.hands).

PRISMATIC_ONLY: rules and guards found on the prismatic hand whose state does not arise on
the 2F-85 linkage hand, so that hand does not run them: a backing cannot hold a caged
object's squeeze on the linkage, and one pad alone cannot press a free-standing object
there long enough, in the approach or hard enough to count, bracket or tip it
(docs/controller.md, "Rules kept to the prismatic hand", which points at the measurements)."""

from tegrasp_drake.robotiq.hand_models import PRISMATIC

PRISMATIC_ONLY = (PRISMATIC,)
