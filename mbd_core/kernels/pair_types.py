"""Contact pair types (``ModelArrays.pair_type``) and the status codes of a force evaluation
(:func:`.forces.compute_forces`)."""



BALL_GROOVE = 0
BALL_BALL = 1
ROLLER_RACEWAY = 2
ROLLER_RIB = 3
ELEMENT_POCKET = 4

STATUS_OK = 0
STATUS_NONFINITE = 1
STATUS_PENETRATION = 2
STATUS_ENERGY = 3
STATUS_MODAL = 4
STATUS_SQUEEZE_FILM = 5
