export { buildAliasTable, aliasTableDistribution, type AliasTable } from './alias-table.ts';
export { luminance } from './emissive-lights.ts';
