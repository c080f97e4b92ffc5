import type { StreamingDecoder } from './dbss.mjs';

export interface FetchOptions { onPiece?: (bytes: number) => void; signal?: AbortSignal }

/** Pushes every piece of a response body into the decoder. */
export function pushBody(response: Response, decoder: StreamingDecoder, onPiece?: (bytes: number) => void): Promise<number>;
/** Streams the whole file (fetch()'s body) and finishes; throws DbssError. */
export function streamAll(url: string, decoder: StreamingDecoder, options?: FetchOptions): Promise<void>;
/** End of level `level`'s chunk from the table of contents (null before it is in). */
export function levelEnd(decoder: StreamingDecoder, level: number): number | null;
/** HTTP Range requests for the table of contents, then bytes up to level L's chunk. */
export function fetchUpToLevel(url: string, decoder: StreamingDecoder, level: number, options?: FetchOptions): Promise<void>;
/** A Range request for the next level; false when every level is in. */
export function fetchNextLevel(url: string, decoder: StreamingDecoder, options?: FetchOptions): Promise<boolean>;
