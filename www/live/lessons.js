// The lessons: each a link's query (engine parameters and the page's view:
// speed, layers, race), or a few steps each with its query, a few plain
// sentences, what to look at, and the claim it shows. tests/e2e/lessons.test.mjs checks every claim with the
// engine on the lesson's own settings. Pure data: no DOM.

export const LESSONS = [
  {
    id: 'phases',
    title: 'One loop, phase by phase',
    query: 'n=11&sigma=2&loops=40&seed=3&start=2,2&variant=tree&keep_traces=3&speed=1s&show=visits,path,intent,grid,arrows,rollouts,practice',
    text: 'Each MCTS loop has four phases. Select walks down the tree by UCT; Expand adds one node; Roll out walks at random from it until it detects the practice target (◇); Back up adds the reward to every node on the way.',
    look: 'Watch the phase strip and the line under it. In the tree, the selection is yellow, the new node ringed, the rollout dashed, and the back-up climbs to the root. Pause and press p for one phase, Shift+← to go back one.',
    claim: 'Every loop runs the four phases in order, and each loop adds one visit to the root.',
  },
  {
    id: 'uct-c',
    title: 'UCT and the exploration constant c',
    query: 'n=15&sigma=3&loops=60&seed=5&variant=tree&c=0.2&vs=c=3&speed=1&show=visits,path,grid,arrows,rollouts,practice',
    text: 'UCT scores a move by its mean reward plus c·√(ln N / Nᵢ). A small c trusts the means and keeps picking the move that looks best; a large c spreads the loops over all four moves.',
    look: 'Board A has c = 0.2, board B c = 3, on the same target. Compare the decision arrows: A’s are lopsided, B’s even. The tree view shows A’s tree; its Board B button shows B’s.',
    claim: 'Over a decision, the most picked move takes a larger share of the loops with c = 0.2 than with c = 3.',
  },
  {
    id: 'theorem1',
    title: 'Theorem 1: more loops, a shorter path',
    steps: [
      { label: 'L = 10 vs 100', query: 'prior=delta&seed=5&loops=10&vs=loops=100&speed=20&show=visits,path,grid,arrows,rollouts,practice' },
      { label: 'L = 100 vs 1000', query: 'prior=delta&seed=5&loops=100&vs=loops=1000&speed=100&show=visits,path,grid,arrows,rollouts,practice' },
    ],
    text: 'When the target’s cell is known (a delta prior), the paper proves that MCTS’s move tends to the optimal one as the loops per move L grow. Step 1 races L = 10 against L = 100 from the same start; step 2 races L = 100 against L = 1000.',
    look: 'Watch the two paths and the scoreboard: the path with more loops heads straighter for the target. Then run a batch: it compares both on the same trials.',
    claim: 'On the same targets, the steps over the shortest path fall from L = 10 to L = 100 to L = 1000.',
  },
  {
    id: 'theorem2',
    title: 'Theorem 2: a nearly self-avoiding walk',
    query: 'prior=uniform&n=60&rv=1&loops=50&rollout_cap=2000&seed=3&race=rw&speed=5&show=visits,path,grid',
    text: 'When every cell is equally likely (a uniform prior), the paper proves that MCTS with random-walk rollouts behaves like a walk that avoids its own path: stepping back onto a searched cell gains nothing. A random walk, raced beside it, keeps stepping back.',
    look: 'Compare the two paths and the Revisits count under This run (board A) with the scoreboard: MCTS almost never revisits a cell.',
    claim: 'Over their first 60 moves, MCTS revisits under 5% of its moves; the random walk over 25%.',
  },
  {
    id: 'levy',
    title: 'Random-walk against Lévy rollouts',
    query: 'preset=paper-code&prior=delta&seed=5&loops=100&vs=rollout=levy&speed=20&show=visits,path,grid,arrows,rollouts,practice',
    text: 'A rollout can be a random walk (one cell a step) or a Lévy flight (straight flights of heavy-tailed lengths). The paper reports that Lévy rollouts search better; with our Lévy law, on a known target (the paper-code reading), they do not.',
    look: 'Board A rolls out random walks, board B Lévy flights, on the same target. Compare the rollout trails and the scoreboard, then run a batch for the paired difference.',
    claim: 'On the same targets, MCTS with Lévy rollouts takes more steps than with random-walk rollouts.',
  },
  {
    id: 'belief',
    title: 'The paper’s MCTS, the belief MCTS and the bound',
    query: 'preset=paper-code&sigma=5&seed=5&loops=100&vs=variant=pomcp&speed=20&show=posterior,path,grid,arrows',
    text: 'The paper’s MCTS keeps one table of counts per cell for the whole search. The belief MCTS (pomcp) plans each move afresh from the belief, with searched cells removed. No searcher can average fewer steps than the bound the page states at the end.',
    look: 'Board A is the paper’s MCTS, board B the belief MCTS, on the same target. When both have found it, compare their steps with the Bound on mean steps under This run; a batch compares them on many targets.',
    claim: 'On the same targets, the belief MCTS takes fewer steps than the paper’s MCTS: its mean is closer to the bound.',
  },
];

/** The lesson with id `id`, or undefined. */
export const lessonById = (id) => LESSONS.find((l) => l.id === id);

/** A lesson's steps, each `{ label, query }` (one, its own query, for a lesson without steps). */
export const lessonSteps = (lesson) => lesson.steps ?? [{ label: '', query: lesson.query }];

/**
 * A link's `lesson` value, `ID` or `ID.STEP` (steps count from 1), as
 * `{ lesson, step }` (step from 0), or undefined if it names no lesson or no step of it.
 */
export function lessonAt(value) {
  const m = /^([a-z0-9-]+)(?:\.(\d{1,3}))?$/.exec(String(value ?? ''));
  const lesson = m && lessonById(m[1]);
  if (!lesson) return undefined;
  const step = m[2] === undefined ? 0 : Number(m[2]) - 1;
  return step >= 0 && step < lessonSteps(lesson).length ? { lesson, step } : undefined;
}

/** The link's `lesson` value for step `step` (from 0) of `lesson`. */
export const lessonValue = (lesson, step) => (step > 0 ? `${lesson.id}.${step + 1}` : lesson.id);
