"""Keepaway 3v2, the decision-level task: the env (:mod:`.env`), the keepers' behaviours
between decisions (:mod:`.keepers`), the takers (:mod:`.takers`), observations and state
(:mod:`.observation`), parameters (:mod:`.params`) and benchmark policies
(:mod:`.policies`)."""
