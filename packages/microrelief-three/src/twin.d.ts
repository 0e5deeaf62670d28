// Declarations of twin.js (hand-written; tests/three's typecheck holds them to the module).
import type {ReliefMap} from './pyramid.js';
import type {Relief, TracedRays} from './relief.js';

/** At most this many twins (height scale, base, last level) a map keeps; the one used longest ago goes first. */
export const kMaxTwinsPerMap: number;
/** Loads the WebAssembly twin once (createReliefMap awaits it); never throws. */
export function loadTwin(): Promise<unknown>;
/** Whether picks can be traced by the twin now. */
export function twinLoaded(): boolean;
/** Why the twin cannot trace ('' when it can). */
export function twinUnavailable(): string;
/** World rays traced by the twin (traceRays's arguments). */
export function traceOnTwin(relief: Relief, origins: ArrayLike<number>, directions: ArrayLike<number>, ranges: ArrayLike<number>): TracedRays;
/** WebAssembly memory of `reliefMap`'s twins, bytes. */
export function twinBytes(reliefMap: ReliefMap): number;
/** Twins held, all maps together. */
export function twinCount(): number;
/** Frees `reliefMap`'s twins (ReliefMap.dispose). */
export function releaseTwins(reliefMap: ReliefMap): void;
