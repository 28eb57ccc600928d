"""The hands a taxel_aware rule, guard or sense is kept to (Rule.hands, Guard.hands, the
estimator's film strike).

PRISMATIC_ONLY: rules and guards found on the prismatic hand whose state does not arise on
the 2F-85 linkage hand, so that hand does not run them: a backing cannot hold a caged
object's squeeze on the linkage, and one pad alone cannot press a free-standing object
there long enough, in the approach or hard enough to count, bracket or tip it
(docs/controller.md, "Rules kept to the prismatic hand", which points at the measurements).

LINKAGE_ONLY: rules whose state arises only on the 2F-85 linkage hand: fingertips that curl
past an object and hook its far side (curled_fingertips.py); a prismatic pad has no distal
link to curl.

FILM_STRIKE_HANDS: the hands on which one film's RA onset in the approach counts as a finger
strike (estimator.ContactEstimator, finger_strike.py): the linkage hand, whose open finger's
front meets a face in the approach with a wrist force far below finger_strike.force_n; on
the prismatic hand a pad that touches in the approach is the approach_contact rule's, which
the film would pre-empt (docs/controller.md, "Finger strike")."""

from tegrasp_drake.robotiq.hand_models import LINKAGE, PRISMATIC

PRISMATIC_ONLY = (PRISMATIC,)
LINKAGE_ONLY = (LINKAGE,)
FILM_STRIKE_HANDS = (LINKAGE,)
