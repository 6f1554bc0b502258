"""Playing recordings: ``pge play``.

``control`` is the player's state machine (pure: state + key -> state, state
+ wall time -> state), ``history`` the event list, ``screen`` what one screen
shows, ``player`` the loop that ties them to a display (a pygame window, or
none when headless).
"""

from pge.playback.control import PlayerState, press, start, tick
from pge.playback.player import NoWindow, PlaySummary, play

__all__ = ["play", "PlaySummary", "NoWindow", "PlayerState", "start", "tick", "press"]
